#include "rpsd/realtime/cpu_wake_latency.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <utility>

namespace rpsd::realtime {

CpuWakeLatencyHold::CpuWakeLatencyHold(int max_latency_us, const char* device) {
  const int fd = ::open(device, O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    refused_ = std::string(device) + ": " + std::strerror(errno);
    return;
  }
  const std::int32_t value = max_latency_us;
  if (::write(fd, &value, sizeof value) != static_cast<ssize_t>(sizeof value)) {
    refused_ = std::string(device) + ": write refused: " + std::strerror(errno);
    ::close(fd);
    return;
  }
  fd_ = fd;
}

CpuWakeLatencyHold::~CpuWakeLatencyHold() {
  if (fd_ >= 0) ::close(fd_);
}

CpuWakeLatencyHold::CpuWakeLatencyHold(CpuWakeLatencyHold&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), refused_(std::move(other.refused_)) {}

CpuWakeLatencyHold& CpuWakeLatencyHold::operator=(CpuWakeLatencyHold&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    refused_ = std::move(other.refused_);
  }
  return *this;
}

int current_cpu_wake_latency_limit_us() {
  const int fd = ::open(kPmQosDevice, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return -1;
  std::int32_t value = -1;
  const bool ok = ::read(fd, &value, sizeof value) == static_cast<ssize_t>(sizeof value);
  ::close(fd);
  return ok ? value : -1;
}

}  // namespace rpsd::realtime
