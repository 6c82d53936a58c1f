// Keeps the CPUs out of idle states while a real-time loop runs. An idle CPU that halts takes
// time to wake: on this project's 2-core VM (cpuidle driver haltpoll, no guest polling) an
// empty loop paced at 4096 Hz with SCHED_FIFO woke a whole period late on 4.4 % of its cycles
// while the machine was otherwise idle, and on 0.11 % while the CPUs were kept from halting
// (bench/realtime_floor). The kernel's PM QoS interface does that: a process writes the
// largest wake-up latency it accepts, in microseconds, to /dev/cpu_dma_latency and keeps the
// file open; 0 leaves only the polling idle state. The request ends when the file is closed
// (or the process exits). It costs power and, on a shared host, CPU time: idle CPUs spin.
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
