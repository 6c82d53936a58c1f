// What a run is doing, for a progress display: the phase, the case of a sweep (1-based), and
// the steps of a phase that has them. Not real-time safe: as fast as possible the loop reports
// every ~0.5 s of test time; in real time the recorder's writer thread does (run_watchers.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>

namespace rpsd::hybrid_test {

struct ProgressReport {
  std::string_view phase;  // "test", "plots", "sweep table"
  std::size_t case_number = 1, cases = 1;
  std::int64_t done = 0, planned = 0;  // 0 planned: a phase without steps
  // A real-time run's, reported from the recorder's writer thread (never the loop's): the
  // paced cycles that missed their deadline and the oldest feedback used so far (periods).
  bool real_time = false;
  std::int64_t overruns = 0;
  int worst_feedback_age_periods = 0;
};

using ProgressSink = std::function<void(const ProgressReport&)>;

}  // namespace rpsd::hybrid_test
