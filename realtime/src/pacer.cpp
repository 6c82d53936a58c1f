#include "rpsd/realtime/pacer.h"

#include <cerrno>
#include <ctime>
#include <stdexcept>

namespace rpsd::realtime {

namespace {
constexpr std::int64_t kNsPerS = 1'000'000'000;

timespec to_timespec(std::int64_t ns) {
  return timespec{static_cast<time_t>(ns / kNsPerS), static_cast<long>(ns % kNsPerS)};
}
}  // namespace

std::int64_t monotonic_now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

void sleep_until_ns(std::int64_t deadline_ns) {
  const timespec ts = to_timespec(deadline_ns);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

Pacer::Pacer(std::int64_t period_ns) : period_ns_(period_ns) {
  if (period_ns <= 0) throw std::invalid_argument("Pacer: the period must be positive");
}

void Pacer::start() {
  deadline_ns_ = monotonic_now_ns() + period_ns_;
  cycles_ = overruns_ = skipped_ = 0;
}

std::int64_t Pacer::wait_next() {
  ++cycles_;
  std::int64_t now = monotonic_now_ns();
  if (now > deadline_ns_) {
    // The work of this cycle ended after the deadline it should have slept until.
    ++overruns_;
    const std::int64_t missed = (now - deadline_ns_) / period_ns_;
    skipped_ += missed;
    deadline_ns_ += missed * period_ns_;
    // Run the next cycle at once (it is late already) and stay on the grid after it.
    const std::int64_t late = now - deadline_ns_;
    deadline_ns_ += period_ns_;
    return late;
  }
  sleep_until_ns(deadline_ns_);
  now = monotonic_now_ns();
  const std::int64_t late = now - deadline_ns_;
  deadline_ns_ += period_ns_;
  return late > 0 ? late : 0;
}

}  // namespace rpsd::realtime
