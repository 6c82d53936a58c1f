// What a host gives a paced loop that does nothing: the floor under every real-time figure of
// rpsd on it. One thread paced to absolute deadlines (Pacer, as the coordinator and the node
// pace) with no work: an overrun here is a wake-up later than the next deadline, time the host
// did not give the thread, so no loop with work in it can overrun less often on that host.
// Used by `rpsd host-check` (a lab's own PC) and bench/realtime_floor (the benchmark report).
// Not real-time safe, except the loop inside measure_empty_loop.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rpsd/realtime/latency_histogram.h"

namespace rpsd::realtime {

// Jiffies of all CPUs together (/proc/stat's "cpu" line): everything, and the part the
// hypervisor stole (on a VM, time the host ran someone else).
struct CpuTimes {
  long long total = 0, steal = 0;
};
// The first line of a /proc/stat text; throws std::runtime_error when it is not a "cpu" line.
CpuTimes parse_cpu_times(const std::string& proc_stat);
// This host's, from /proc/stat (zeros when it cannot be read).
CpuTimes read_cpu_times();
// Percent of the CPU time between two readings that was stolen; 0 when no time passed.
double steal_percent(const CpuTimes& before, const CpuTimes& after);

// One rate's empty paced loop.
struct EmptyLoopFloor {
  int rate_hz = 0;
  bool cpus_kept_awake = false;
  std::int64_t cycles = 0, overruns = 0, skipped_deadlines = 0;
  LatencySummary wakeup;  // each wake-up's lateness past its deadline
  double steal_percent = 0.0;
  // overruns / cycles in percent (0 with no cycles).
  double overruns_percent() const;
};

// Paces `cycles` empty cycles on `pacer` (started here) and tallies them. A template so that a
// test can count with a pacer of its own (a fake clock); measure_empty_loop uses Pacer.
template <class PacerLike>
EmptyLoopFloor tally_empty_loop(PacerLike& pacer, int rate_hz, std::int64_t cycles) {
  LatencyHistogram lateness;
  pacer.start();
  while (pacer.cycles() < cycles) lateness.add(pacer.wait_next());
  EmptyLoopFloor floor;
  floor.rate_hz = rate_hz;
  floor.cycles = pacer.cycles();
  floor.overruns = pacer.overruns();
  floor.skipped_deadlines = pacer.skipped_deadlines();
  floor.wakeup = lateness.summary();
  return floor;
}

// The empty loop at `rate_hz` for `seconds` on the calling thread, as it is scheduled now
// (apply_realtime first for SCHED_FIFO), with the steal time over the run. Throws
// std::invalid_argument for a rate or duration that is not positive.
EmptyLoopFloor measure_empty_loop(int rate_hz, double seconds, bool cpus_kept_awake);

// One CPU idle state (cpuidle in sysfs) as CPU 0 has it.
struct IdleState {
  std::string name;
  int exit_latency_us = -1;      // the time to wake from it
  bool disabled = false;         // disabled on CPU 0 now
  bool can_be_disabled = false;  // its `disable` file is writable by this process
};
struct IdleStates {
  std::string driver;  // cpuidle's current driver; empty when the host has no cpuidle
  std::vector<IdleState> states;
  int cpus = 0;  // CPUs with a cpuidle folder
};
// Reads `cpu_root` (normally /sys/devices/system/cpu); a missing file leaves its field default.
IdleStates read_idle_states(const std::string& cpu_root = "/sys/devices/system/cpu");

}  // namespace rpsd::realtime
