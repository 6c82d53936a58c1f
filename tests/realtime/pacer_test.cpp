// Behaviour, not speed: deadlines stay ordered on the grid, and a long cycle is counted as
// an overrun with the deadlines it skipped, never replayed as a burst.
#include "rpsd/realtime/pacer.h"

#include <gtest/gtest.h>

#include <thread>

namespace rpsd::realtime {
namespace {

constexpr std::int64_t kPeriodNs = 2'000'000;

TEST(Pacer, WakesNeverBeforeItsDeadlineAndAdvancesOnePeriodPerCycle) {
  Pacer pacer(kPeriodNs);
  pacer.start();
  std::int64_t previous_deadline = pacer.current_deadline_ns();
  for (int k = 0; k < 20; ++k) {
    EXPECT_GE(pacer.wait_next(), 0);
    // Woken at or after the deadline just passed.
    EXPECT_GE(monotonic_now_ns(), pacer.current_deadline_ns());
    EXPECT_GE(pacer.current_deadline_ns() - previous_deadline, kPeriodNs);
    EXPECT_EQ((pacer.current_deadline_ns() - previous_deadline) % kPeriodNs, 0);
    previous_deadline = pacer.current_deadline_ns();
  }
  EXPECT_EQ(pacer.cycles(), 20);
}

TEST(Pacer, ALongCycleIsOneOverrunAndSkipsTheDeadlinesItMissed) {
  Pacer pacer(kPeriodNs);
  pacer.start();
  pacer.wait_next();
  const std::int64_t overruns_before = pacer.overruns();
  const std::int64_t skipped_before = pacer.skipped_deadlines();
  const std::int64_t deadline_before = pacer.current_deadline_ns();
  std::this_thread::sleep_for(std::chrono::nanoseconds(3 * kPeriodNs + kPeriodNs / 2));
  const std::int64_t late = pacer.wait_next();
  EXPECT_EQ(pacer.overruns(), overruns_before + 1);
  EXPECT_GE(pacer.skipped_deadlines() - skipped_before, 2);
  // It runs the late cycle at once and returns to the grid: the deadline it now stands on is
  // the last one passed, on the grid, and lateness is measured from it (whatever else the
  // machine did, so nothing here depends on the next cycle being on time).
  const std::int64_t advanced_ns = pacer.current_deadline_ns() - deadline_before;
  EXPECT_EQ(advanced_ns % kPeriodNs, 0);
  EXPECT_GE(advanced_ns, 3 * kPeriodNs);
  EXPECT_EQ(advanced_ns / kPeriodNs - 1, pacer.skipped_deadlines() - skipped_before);
  EXPECT_GE(late, 0);
  EXPECT_LT(late, kPeriodNs);
}

TEST(Pacer, RejectsANonPositivePeriod) { EXPECT_THROW(Pacer(0), std::invalid_argument); }

}  // namespace
}  // namespace rpsd::realtime
