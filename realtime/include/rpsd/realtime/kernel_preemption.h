// Whether the running kernel preempts its own code for a real-time thread. Without forced
// preemption (the models none and voluntary), a SCHED_FIFO thread woken while another task is
// in the kernel (a compiler's page faults and file I/O, a network softirq) waits until that
// code reaches a preemption point: milliseconds, beyond any empty loop's floor, in every
// wake-up of a distributed loop's chain (docs/realtime.md). `rpsd host-check` reports it.
// Not real-time safe.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace rpsd::realtime {

enum class PreemptionModel { kUnknown, kNone, kVoluntary, kFull, kLazy, kRealTime };

// "unknown", "none", "voluntary", "full", "lazy", "rt": the kernel's own words (preempt=).
std::string_view preemption_name(PreemptionModel model);

// Full, lazy (which defers only the fair class) and PREEMPT_RT preempt kernel code at once
// for a real-time thread; none and voluntary do not, and unknown is not assumed to.
bool preempts_for_real_time(PreemptionModel model);

struct KernelPreemption {
  PreemptionModel model = PreemptionModel::kUnknown;
  std::string source;  // where it was read, for the report
};

// Where the model is read, in this order: a PREEMPT_RT kernel's flag file and version; the
// scheduler's debugfs file (root, "none voluntary (full) lazy"); a preempt= boot parameter
// of a PREEMPT_DYNAMIC kernel; the build's default in the kernel configuration. Tests point
// the paths elsewhere; an empty `version` is read with uname(2).
struct KernelFiles {
  std::filesystem::path realtime_flag = "/sys/kernel/realtime";
  std::filesystem::path debugfs_preempt = "/sys/kernel/debug/sched/preempt";
  std::filesystem::path cmdline = "/proc/cmdline";
  std::filesystem::path config_gz = "/proc/config.gz";
  std::string version;  // as `uname -v` prints it
};

KernelPreemption read_kernel_preemption(const KernelFiles& files = {});

}  // namespace rpsd::realtime
