// What a real-time process asks of the OS before its loop starts: locked memory (no page
// faults in the loop), large blocks kept out of the heap (a long run must not grow;
// large_blocks.h), a SCHED_FIFO priority, the loop's own CPU (one a lab isolated with
// isolcpus=, where nothing else runs), and CPUs kept out of slow idle states
// (cpu_wake_latency.h). Each may be refused (no privilege, a container): the loop then still
// runs, and the refusal is reported once, not fatal.
#pragma once

#include <string>

#include "rpsd/realtime/cpu_wake_latency.h"

namespace rpsd::realtime {

struct RealTimeRequest {
  bool lock_memory = true;
  int fifo_priority = 80;  // 1..99; 0 keeps the default scheduler
  // The CPU the calling thread (the loop) is pinned to; -1 leaves it to the scheduler.
  int loop_cpu = -1;
  // Keep every CPU out of idle states that take time to wake (cpu_wake_latency.h).
  bool keep_cpus_awake = true;
};

struct RealTimeSetupReport {
  bool memory_locked = false;
  bool fifo_granted = false;
  bool cpus_kept_awake = false;
  int pinned_cpu = -1;  // the loop's CPU when pinning was asked and granted
  std::string refused;  // one line per refusal with the OS's reason; empty when all granted
};

// Applies the request to the calling process/thread. Not real-time safe.
RealTimeSetupReport apply_realtime(const RealTimeRequest& request);

// The request's keep_cpus_awake, for as long as the returned hold lives (keep it for the
// loop's run); its outcome goes into `report` (cpus_kept_awake, or a line in refused).
// Not real-time safe.
CpuWakeLatencyHold hold_cpus_awake(const RealTimeRequest& request, RealTimeSetupReport& report);

}  // namespace rpsd::realtime
