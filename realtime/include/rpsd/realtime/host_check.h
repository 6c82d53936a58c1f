// A host's real-time floor, as a lab checks its PC before a test (`rpsd host-check`) and the
// benchmark report measures it (bench/realtime_floor): what the OS granted of rpsd's
// real-time request (SCHED_FIFO, locked memory), which CPU idle states exist and whether the
// CPUs can be kept out of them, and the empty paced loop at each rate (host_floor.h), first
// with the CPUs free to idle, then kept awake as rpsd's real-time loops keep them.
// Not real-time safe.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rpsd/realtime/host_floor.h"
#include "rpsd/realtime/kernel_preemption.h"
#include "rpsd/realtime/realtime_setup.h"

namespace rpsd::realtime {

struct HostCheckRequest {
  std::vector<int> rates_hz{1024, 2048, 4096};
  double seconds_per_rate = 10.0;
  int fifo_priority = 80;  // rpsd's loops' default
};

struct HostCheckReport {
  HostCheckRequest request;
  RealTimeSetupReport granted;  // SCHED_FIFO and mlockall for this thread and process
  KernelPreemption kernel;      // whether the kernel preempts its own code for a real-time thread
  IdleStates idle;
  bool cpus_could_be_kept_awake = false;
  std::string keep_awake_refused;  // the OS's reason when they could not
  int wake_latency_limit_us = -1;  // the PM QoS limit in force before the check (-1: unreadable)
  // The loops: every rate with the CPUs free to idle, then every rate kept awake (when they
  // could be kept awake).
  std::vector<EmptyLoopFloor> loops;
};

// Applies rpsd's real-time request to the calling thread (it stays applied) and measures.
// Throws std::invalid_argument for no rates, a rate that is not positive or a duration that is
// not positive.
HostCheckReport check_host(const HostCheckRequest& request);

// The report as JSON: granted (sched_fifo, mlockall, refused), kernel (preemption, source,
// preempts_for_real_time), cpu_idle (driver, cpus, states,
// can_keep_cpus_awake, keep_awake_refused, wake_latency_limit_us) and loops (one per rate and
// idle setting: rate_hz, cpus_kept_awake, cycles, overruns, overruns_percent,
// skipped_deadlines, wakeup as latency_json, steal_percent).
nlohmann::json host_check_json(const HostCheckReport& report);

}  // namespace rpsd::realtime
