#include "rpsd/realtime/realtime_setup.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cstring>
#include <stdexcept>

#include "rpsd/realtime/large_blocks.h"

namespace rpsd::realtime {

RealTimeSetupReport apply_realtime(const RealTimeRequest& request) {
  if (request.fifo_priority < 0 || request.fifo_priority > 99) {
    throw std::invalid_argument("realtime.fifo_priority: expected 0 (off) or 1..99, got " +
                                std::to_string(request.fifo_priority));
  }
  RealTimeSetupReport report;
  // Before the loop starts: a run of hours must not grow the heap (large_blocks.h).
  if (!map_large_blocks_separately()) report.refused += "mallopt(M_MMAP_THRESHOLD) refused\n";
  if (request.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      report.memory_locked = true;
    } else {
      report.refused += std::string("mlockall refused: ") + std::strerror(errno) + "\n";
    }
  }
  if (request.fifo_priority > 0) {
    sched_param param{};
    param.sched_priority = request.fifo_priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (rc == 0) {
      report.fifo_granted = true;
    } else {
      report.refused +=
          "SCHED_FIFO priority " + std::to_string(request.fifo_priority) + " refused: " + std::strerror(rc) + "\n";
    }
  }
  return report;
}

CpuWakeLatencyHold hold_cpus_awake(const RealTimeRequest& request, RealTimeSetupReport& report) {
  if (!request.keep_cpus_awake) return {};
  CpuWakeLatencyHold hold(0);
  report.cpus_kept_awake = hold.held();
  if (!hold.held()) report.refused += "keeping the CPUs awake refused: " + hold.refused() + "\n";
  return hold;
}

}  // namespace rpsd::realtime
