// Keeps the CPUs out of idle states while a real-time loop runs, because a CPU that halts wakes too
// slowly for a paced loop. A PM QoS request (0 us written to /dev/cpu_dma_latency, the file kept open)
// leaves only the polling idle state until the file is closed or the process exits. It costs power
// and, on a shared host, CPU time: idle CPUs spin. Measurements: docs/realtime.md
#pragma once

#include <string>

namespace rpsd::realtime {

inline constexpr const char* kPmQosDevice = "/dev/cpu_dma_latency";

class CpuWakeLatencyHold {
 public:
  // Holds nothing.
  CpuWakeLatencyHold() = default;
  // Requests a wake-up latency of at most `max_latency_us` for every CPU through `device`.
  // Never throws on a refusal (no such device, no permission): held() is then false and
  // refused() says why.
  explicit CpuWakeLatencyHold(int max_latency_us, const char* device = kPmQosDevice);
  ~CpuWakeLatencyHold();
  CpuWakeLatencyHold(CpuWakeLatencyHold&& other) noexcept;
  CpuWakeLatencyHold& operator=(CpuWakeLatencyHold&& other) noexcept;
  CpuWakeLatencyHold(const CpuWakeLatencyHold&) = delete;
  CpuWakeLatencyHold& operator=(const CpuWakeLatencyHold&) = delete;

  bool held() const { return fd_ >= 0; }
  const std::string& refused() const { return refused_; }

 private:
  int fd_ = -1;
  std::string refused_;
};

// The system-wide limit now in force, in microseconds (the smallest of all requests, or the
// kernel's default when there is none); -1 when it cannot be read.
int current_cpu_wake_latency_limit_us();

}  // namespace rpsd::realtime
