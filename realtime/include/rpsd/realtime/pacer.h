// Absolute-deadline pacing (clock_nanosleep on CLOCK_MONOTONIC with TIMER_ABSTIME): the
// deadlines stay on the grid t0 + k T whatever one cycle took, so lateness never
// accumulates. A cycle whose work ends after its own next deadline is an overrun: it is
// counted, and the grid skips forward rather than firing a burst of catch-up cycles.
#pragma once

#include <cstdint>

namespace rpsd::realtime {

// Nanoseconds on CLOCK_MONOTONIC. Real-time safe.
std::int64_t monotonic_now_ns();
// Sleeps until the absolute CLOCK_MONOTONIC time. Real-time safe.
void sleep_until_ns(std::int64_t deadline_ns);

class Pacer {
 public:
  // Not real-time safe (throws std::invalid_argument for a non-positive period).
  explicit Pacer(std::int64_t period_ns);

  // Sets the first deadline one period from now. Real-time safe.
  void start();

  // Sleeps until the next deadline. Returns the wake-up lateness (jitter) in ns, >= 0.
  // Real-time safe.
  std::int64_t wait_next();

  std::int64_t period_ns() const { return period_ns_; }
  std::int64_t cycles() const { return cycles_; }
  std::int64_t overruns() const { return overruns_; }
  // Deadlines skipped after overruns (each one a control period with no cycle).
  std::int64_t skipped_deadlines() const { return skipped_; }
  // The deadline of the cycle now running.
  std::int64_t current_deadline_ns() const { return deadline_ns_ - period_ns_; }

 private:
  std::int64_t period_ns_;
  std::int64_t deadline_ns_ = 0;
  std::int64_t cycles_ = 0, overruns_ = 0, skipped_ = 0;
};

}  // namespace rpsd::realtime
