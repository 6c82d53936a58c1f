// What a run has done so far, for those who watch it from other threads (the terminal's
// progress, the telemetry's status): the loop's thread stores, others load, all relaxed. A
// lock-free atomic store is all the loop pays: no lock, no allocation, no I/O.
#pragma once

#include <atomic>
#include <cstdint>

namespace rpsd::coordinator {

struct LiveCounters {
  std::atomic<std::int64_t> steps_done{0};
  std::atomic<std::int64_t> overruns{0};       // real time: paced cycles that missed their deadline
  std::atomic<std::int64_t> late_feedback{0};  // exchanges answered by an older measurement
  static_assert(std::atomic<std::int64_t>::is_always_lock_free);
};

}  // namespace rpsd::coordinator
