// What `rpsd run` shows on stderr as a run goes: the phase, the sweep case, the steps, the
// simulated time, the speed and the time left; a real-time run also its overruns and the worst
// feedback age (reported by the recorder's writer thread, never the loop's). On a terminal a
// line redrawn in place once the run has lasted a second; elsewhere (a log, CI) a plain line
// every 5 s.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <mutex>

#include "rpsd/hybrid_test/progress.h"

namespace rpsd::cli {

class ProgressBar {
 public:
  // `out`: where to draw; `terminal`: redraw in place (else plain lines every 5 s).
  ProgressBar(double control_rate_hz, std::FILE* out, bool terminal);
  // On stderr, drawn in place when stderr is a terminal.
  explicit ProgressBar(double control_rate_hz);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  // Any thread, one at a time or not (a real-time run reports from the recorder's thread).
  void operator()(const hybrid_test::ProgressReport& r);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr double kPlainEveryS = 5.0;
  std::mutex mutex_;
  double rate_hz_;
  std::FILE* out_;
  bool terminal_;
  Clock::time_point start_, case_start_, last_plain_;
  std::size_t case_number_ = 1;
  bool drawn_ = false;
};

}  // namespace rpsd::cli
