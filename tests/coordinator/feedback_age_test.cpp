// Late feedback in real time: the loop carries on with the newest measurement while it is
// at most max_feedback_age_periods behind, and stops when a node falls silent. A constant
// lag of one period is one more period of delay, so the damping must be the exact DDE
// root's for the plant's delay plus one period.
#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <vector>

#include "rpsd/compensation/delay_theory.h"
#include "rpsd/studies/damping_identification.h"
#include "specimen_runs.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

// Delivers each feedback `lag` exchanges late (as a real-time link does when the round
// trip exceeds the period: the newest sample, with kTimeout), and none at all from
// exchange `silent_from` on. With `lease_lapsed`, a late answer comes with kPeerLost, as
// from a DdsLink whose node's liveliness lease lapsed while the host stalled.
class LaggingLink final : public transport::Link {
 public:
  LaggingLink(transport::Link& inner, int lag, std::int64_t silent_from, bool lease_lapsed)
      : inner_(inner), lag_(lag), silent_from_(silent_from), lease_lapsed_(lease_lapsed) {}
  transport::LinkStatus send(const transport::CommandSample& command) override {
    exchange_ = command.step;
    if (inner_.send(command) != transport::LinkStatus::kOk) return transport::LinkStatus::kPeerLost;
    transport::FeedbackSample f;
    if (inner_.receive(f) != transport::LinkStatus::kOk) return transport::LinkStatus::kPeerLost;
    if (exchange_ < silent_from_) in_flight_.push_back(f);
    return transport::LinkStatus::kOk;
  }
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override {
    // The first exchange always arrives (the real-time loop waits for it without a deadline).
    while (!in_flight_.empty() && (in_flight_.front().step + lag_ <= exchange_ || in_flight_.front().step == 0)) {
      newest_ = in_flight_.front();
      in_flight_.pop_front();
    }
    feedback = newest_;
    if (newest_.step == exchange_) return transport::LinkStatus::kOk;
    return lease_lapsed_ ? transport::LinkStatus::kPeerLost : transport::LinkStatus::kTimeout;
  }

 private:
  transport::Link& inner_;
  int lag_;
  std::int64_t silent_from_;
  bool lease_lapsed_;
  std::int64_t exchange_ = -1;
  std::deque<transport::FeedbackSample> in_flight_;
  transport::FeedbackSample newest_{};
};

// The test in real time (late feedback tolerated up to 4 periods) but stepped without
// pacing, or in lock-step, its link lagging as LaggingLink does.
struct LaggingTest {
  SpecimenSdof sdof;
  int lag = 0;
  std::int64_t silent_from = 1 << 30;
  bool lease_lapsed = false;
  bool real_time = true;
};

LaggingTest lagging(int lag, std::int64_t silent_from, bool lease_lapsed, bool real_time) {
  LaggingTest t;
  t.lag = lag;
  t.silent_from = silent_from;
  t.lease_lapsed = lease_lapsed;
  t.real_time = real_time;
  return t;
}

testing::SdofRun run(const LaggingTest& t) {
  TestConfig config = specimen_sdof_test(t.sdof);
  if (t.real_time) config.clock.mode = ClockConfig::Mode::kRealTime;
  config.clock.max_feedback_age_periods = 4;
  AssemblyOptions options;
  options.wrap_link = [t](transport::Link& inner) {
    return std::make_unique<LaggingLink>(inner, t.lag, t.silent_from, t.lease_lapsed);
  };
  return testing::run_steps(config, options);
}

// One second of the test against a plant without delay: what matters is the link.
testing::SdofRun run_one_second(LaggingTest t) {
  t.sdof.duration_s = 1.0;
  return run(t);
}

TEST(FeedbackAge, OnePeriodLateFeedbackIsOneMorePeriodOfDelay) {
  const double plant_delay_s = 0.004;
  LaggingTest t;
  t.lag = 1;
  t.sdof.duration_s = 12.0;
  t.sdof.plant = servo::PureDelayParameters{plant_delay_s, t.sdof.stiffness_n_per_m, 8192.0, {}, {}};
  const auto r = run(t);
  const SpecimenSdof& setup = t.sdof;
  const double dt_s = 1.0 / setup.control_rate_hz;
  ASSERT_EQ(r.outcome, StepOutcome::kOk);
  ASSERT_EQ(r.records.size(), static_cast<std::size_t>(12.0 / dt_s));
  EXPECT_EQ(r.records[0].feedback_age_periods, 0);
  for (std::size_t n = 1; n < r.records.size(); ++n) ASSERT_EQ(r.records[n].feedback_age_periods, 1) << n;

  const compensation::DelayedOscillator sdof{
      setup.mass_kg, 2.0 * setup.damping_ratio * std::sqrt(setup.stiffness_n_per_m * setup.mass_kg), 0.0,
      setup.stiffness_n_per_m};
  const double exact = compensation::damping_ratio_of(compensation::dominant_root(sdof, plant_delay_s + dt_s));
  const double without_lag = compensation::damping_ratio_of(compensation::dominant_root(sdof, plant_delay_s));
  const studies::IdentifiedDamping identified = studies::identify_damping(testing::displacements(r), dt_s, 0.0, 1e-6);
  EXPECT_NEAR(identified.damping_ratio, exact, 0.001);
  // The extra period matters: the result is not the one without the lag.
  EXPECT_GT(std::abs(exact - without_lag), 0.004);
}

TEST(FeedbackAge, LateButAnsweringNodeKeepsTheTestGoing) {
  const auto r = run_one_second(lagging(4, 1 << 30, false, true));
  EXPECT_EQ(r.outcome, StepOutcome::kOk);
  EXPECT_EQ(r.records.back().feedback_age_periods, 4);
}

TEST(FeedbackAge, ASilentNodeStopsTheTestOnTheFifthPeriod) {
  const std::int64_t silent_from = 100;
  const auto r = run_one_second(lagging(0, silent_from, false, true));
  EXPECT_EQ(r.outcome, StepOutcome::kLinkFailure);
  // Exchanges 100..103 go on with ages 1..4; the fifth (age 5) stops before recording.
  ASSERT_EQ(r.records.size(), static_cast<std::size_t>(silent_from + 4));
  for (int k = 1; k <= 4; ++k) EXPECT_EQ(r.records[silent_from + k - 1].feedback_age_periods, k);
}

// A liveliness lease that lapsed while feedback kept coming (a host that stalled both
// processes) is judged by the feedback's age, like a timeout: the test goes on.
TEST(FeedbackAge, ALapsedLeaseWithRecentFeedbackKeepsARealTimeTestGoing) {
  const auto r = run_one_second(lagging(4, 1 << 30, true, true));
  EXPECT_EQ(r.outcome, StepOutcome::kOk);
  EXPECT_EQ(r.records.size(), 1024u);
  EXPECT_EQ(r.records.back().feedback_age_periods, 4);
}

TEST(FeedbackAge, ALapsedLeaseAndASilentNodeStillStopOnTheFifthPeriod) {
  const std::int64_t silent_from = 100;
  const auto r = run_one_second(lagging(0, silent_from, true, true));
  EXPECT_EQ(r.outcome, StepOutcome::kLinkFailure);
  ASSERT_EQ(r.records.size(), static_cast<std::size_t>(silent_from + 4));
}

TEST(FeedbackAge, LockStepStopsOnALapsedLease) {
  const auto r = run_one_second(lagging(1, 1 << 30, true, false));
  EXPECT_EQ(r.outcome, StepOutcome::kLinkFailure);
  EXPECT_EQ(r.records.size(), 1u);
}

TEST(FeedbackAge, LockStepStopsOnTheFirstLateFeedback) {
  const auto r = run_one_second(lagging(1, 1 << 30, false, false));
  EXPECT_EQ(r.outcome, StepOutcome::kLinkFailure);
  EXPECT_EQ(r.records.size(), 1u);
}

// A site's node that serves another run (the link says kRefused) stops the test at once with
// its own outcome, in real time too: not late feedback to carry on with, not a silent node.
class RefusingLink final : public transport::Link {
 public:
  RefusingLink(transport::Link& inner, std::int64_t refused_from) : inner_(inner), refused_from_(refused_from) {}
  transport::LinkStatus send(const transport::CommandSample& command) override {
    exchange_ = command.step;
    return inner_.send(command);
  }
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override {
    if (exchange_ < refused_from_) return inner_.receive(feedback);
    transport::FeedbackSample unused;
    inner_.receive(unused);
    return transport::LinkStatus::kRefused;
  }

 private:
  transport::Link& inner_;
  std::int64_t refused_from_;
  std::int64_t exchange_ = -1;
};

TEST(FeedbackAge, ANodeThatRefusesTheRunStopsItAtOnceAndNotAsSilence) {
  for (const bool real_time : {false, true}) {
    TestConfig config = specimen_sdof_test(SpecimenSdof{});
    if (real_time) config.clock.mode = ClockConfig::Mode::kRealTime;
    config.clock.max_feedback_age_periods = 4;
    AssemblyOptions options;
    options.wrap_link = [](transport::Link& inner) { return std::make_unique<RefusingLink>(inner, 100); };
    const testing::SdofRun r = testing::run_steps(config, options);
    EXPECT_EQ(r.outcome, StepOutcome::kRefused) << "real time " << real_time;
    EXPECT_EQ(r.records.size(), 100u) << "real time " << real_time;
  }
}

}  // namespace
}  // namespace rpsd::coordinator
