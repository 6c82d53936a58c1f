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
  if (request.loop_cpu < -1 || request.loop_cpu >= CPU_SETSIZE) {
    throw std::invalid_argument("realtime.loop_cpu: expected -1 (any) or 0.." + std::to_string(CPU_SETSIZE - 1) +
                                ", got " + std::to_string(request.loop_cpu));
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
  if (request.loop_cpu >= 0) {
    // A CPU this host lacks, or one outside the process's cpuset, is refused (EINVAL).
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    CPU_SET(static_cast<std::size_t>(request.loop_cpu), &cpus);
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof cpus, &cpus);
    if (rc == 0) {
      report.pinned_cpu = request.loop_cpu;
    } else {
      report.refused +=
          "pinning the loop to CPU " + std::to_string(request.loop_cpu) + " refused: " + std::strerror(rc) + "\n";
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
