// What a real-time process asks of the OS before its loop starts: locked memory (no page
// faults in the loop), large blocks kept out of the heap (a long run must not grow;
// large_blocks.h) and a SCHED_FIFO priority. Both may be refused (no privilege, a
// container): the loop then still runs, and the refusal is reported once, not fatal.
#pragma once

#include <string>

namespace rpsd::realtime {

struct RealTimeRequest {
  bool lock_memory = true;
  int fifo_priority = 80;  ///< 1..99; 0 keeps the default scheduler
};

struct RealTimeSetupReport {
  bool memory_locked = false;
  bool fifo_granted = false;
  std::string refused;  ///< one line per refusal with the OS's reason; empty when all granted
};

/// Applies the request to the calling process/thread. Not real-time safe.
RealTimeSetupReport apply_realtime(const RealTimeRequest& request);

}  // namespace rpsd::realtime
