// The coordinator's own limits (the second layer beside the servo node's): a command beyond
// its stroke or increment is never sent, and a measured force beyond its bound stops the test
// on the feedback that shows it. Checked on the paper's SDOF in free vibration from 10 mm,
// x(t) = x0 cos(w t) with w = sqrt(700.8e3 / 7080) = 9.949 rad/s (damping 1.1 % neglected over
// the first tenth of a second).
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/config/key_error.h"
#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

// The scenario at another rate, optionally without its compensator (whose order-3
// extrapolation 5 ms ahead amplifies the start's discontinuity more the more steps 5 ms is).
hybrid_test::TestConfig scenario_with_limits(const std::string& limits, int rate_hz = 1024, bool compensated = true) {
  std::ifstream in(rpsd::testing::source_dir() / "tests/coordinator/data/sdof-free-vibration.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string anchor = "    restoring_force: stiffness_times_displacement\n";
  text.replace(text.find(anchor), anchor.size(), anchor + "    limits: " + limits + "\n");
  const std::string rate = "control_rate_hz: 1024";
  text.replace(text.find(rate), rate.size(), "control_rate_hz: " + std::to_string(rate_hz));
  const std::string compensation = "compensation:\n  kind: polynomial_extrapolation\n  order: 3\n  delay_s: 0.005\n";
  if (!compensated) text.erase(text.find(compensation), compensation.size());
  const auto path = std::filesystem::temp_directory_path() / ("rpsd-limits-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  auto file = scenarios::load_study(path);
  std::filesystem::remove(path);
  return std::get<hybrid_test::TestConfig>(file.study);
}

TEST(CoordinatorLimits, ACommandBeyondTheStrokeIsNeverSent) {
  const auto s = scenario_with_limits("{max_stroke_m: 0.009}");
  const TestRun run = run_test(s, {}, false);
  EXPECT_EQ(run.outcome, StepOutcome::kLimit);
  EXPECT_EQ(run.limit_stop.kind, LimitStop::Kind::kStroke);
  EXPECT_EQ(run.limit_stop.channel, 0);
  EXPECT_GT(std::abs(run.limit_stop.value), 0.009);
  EXPECT_EQ(run.steps, 0);  // the very first command (about 10 mm) stays home
}

TEST(CoordinatorLimits, TheIncrementLimitStopsWhereTheVelocityCrossesItAndNoLargerStepLeaves) {
  const double max_increment_m = 50e-6, dt = 1.0 / 1024.0, x0 = 0.01;
  const double omega = std::sqrt(700.8e3 / 7080.0);
  const auto s = scenario_with_limits("{max_increment_m: 50.0e-6}");
  const TestRun run = run_test(s, {}, false);
  ASSERT_EQ(run.outcome, StepOutcome::kLimit);
  EXPECT_EQ(run.limit_stop.kind, LimitStop::Kind::kIncrement);
  // The command is the target extrapolated 5 ms ahead (the scenario compensates a 5 ms
  // delay), so its increment x0 w sin(w (t + 5 ms)) dt reaches 50 um 5 ms before the
  // target's would: at asin(...) / w - 5 ms, step 50.6.
  const double t_cross = std::asin(max_increment_m / (x0 * omega * dt)) / omega - 0.005;
  EXPECT_NEAR(static_cast<double>(run.steps) * dt, t_cross, 4 * dt);
  double previous = x0;
  for (const auto& r : run.records) {
    EXPECT_LE(std::abs(r.command_m[0] - previous), max_increment_m) << "step " << r.step;
    previous = r.command_m[0];
  }
}

// The same limit stated per second (max_velocity_m_per_s) means the same speed at any rate:
// 0.0512 m/s is 50 um per period at 1024 Hz, 25 at 2048 and 12.5 at 4096 (within_envelope
// derives it at the test's period), and it stops the test where the command's velocity
// crosses it, at one time whatever the rate, never letting a larger step leave.
TEST(CoordinatorLimits, AVelocityLimitIsTheIncrementAtTheRateTheTestRuns) {
  const double max_velocity_m_per_s = 0.0512, x0 = 0.01;
  const double omega = std::sqrt(700.8e3 / 7080.0);
  const servo::Envelope rig{0.127, 156.0e3, 1.3};
  for (const int rate_hz : {1024, 2048, 4096}) {
    const double dt = 1.0 / rate_hz;
    CoordinatorLimits stated;
    stated.max_velocity_m_per_s = max_velocity_m_per_s;
    const CoordinatorLimits effective = within_envelope(stated, rig, dt);
    EXPECT_DOUBLE_EQ(effective.max_increment_m, 50e-6 * 1024.0 / rate_hz) << rate_hz;
    EXPECT_EQ(effective.max_velocity_m_per_s, max_velocity_m_per_s) << rate_hz;

    const auto s = scenario_with_limits("{max_velocity_m_per_s: 0.0512}", rate_hz, false);
    EXPECT_EQ(s.experimental[0].limits.max_velocity_m_per_s, max_velocity_m_per_s);
    EXPECT_EQ(s.experimental[0].limits.max_increment_m, CoordinatorLimits::kNone);  // derived when run
    const TestRun run = run_test(s, {}, false);
    ASSERT_EQ(run.outcome, StepOutcome::kLimit) << rate_hz;
    EXPECT_EQ(run.limit_stop.kind, LimitStop::Kind::kIncrement) << rate_hz;
    EXPECT_DOUBLE_EQ(run.limit_stop.bound, max_velocity_m_per_s * dt) << rate_hz;
    // Uncompensated, the command is the target: it reaches 0.0512 m/s at asin(v / (x0 w)) / w,
    // 49 ms (the 5 ms delay's negative damping is negligible so soon).
    const double t_cross = std::asin(max_velocity_m_per_s / (x0 * omega)) / omega;
    EXPECT_NEAR(static_cast<double>(run.steps) * dt, t_cross, 0.002) << rate_hz;
    double previous = x0;
    for (const auto& r : run.records) {
      EXPECT_LE(std::abs(r.command_m[0] - previous), max_velocity_m_per_s * dt) << rate_hz << " Hz, step " << r.step;
      previous = r.command_m[0];
    }
  }
}

// One limit, one statement: per period or per second, never both (which would one mean?).
TEST(CoordinatorLimits, AnIncrementAndAVelocityBothGivenAreRefusedWithFileLineAndKey) {
  try {
    scenario_with_limits("{max_increment_m: 0.001, max_velocity_m_per_s: 1.0}");
    ADD_FAILURE() << "both were accepted";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rpsd-limits-"), std::string::npos) << what;  // the file
    EXPECT_NE(what.find(".yaml:16:"), std::string::npos) << what;     // its line
    EXPECT_NE(what.find("experimental[0].limits.max_velocity_m_per_s"), std::string::npos) << what;
    EXPECT_NE(what.find("not both"), std::string::npos) << what;
  }
  // Built in code: the same refusal, naming the key.
  CoordinatorLimits both;
  both.max_increment_m = 0.001;
  both.max_velocity_m_per_s = 1.0;
  EXPECT_THROW(within_envelope(both, servo::Envelope{0.127, 156.0e3, 1.3}, 1.0 / 1024), config::KeyError);
}

// A velocity limit beyond the rig's velocity capacity is refused, as an increment beyond it
// over one period is, naming the key the file gave.
TEST(CoordinatorLimits, AVelocityBeyondTheRigsCapacityIsRefusedWithItsKey) {
  try {
    scenario_with_limits("{max_velocity_m_per_s: 1.5}", 4096);  // the rig: 1.3 m/s
    ADD_FAILURE() << "1.5 m/s was accepted";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("experimental[0].limits.max_velocity_m_per_s"), std::string::npos) << what;
    EXPECT_NE(what.find("beyond the rig's velocity capacity of 1.3"), std::string::npos) << what;
  }
  // At the capacity itself it stands, at every rate.
  for (const int rate_hz : {1024, 2048, 4096}) {
    EXPECT_NO_THROW(scenario_with_limits("{max_velocity_m_per_s: 1.3}", rate_hz)) << rate_hz;
  }
}

TEST(CoordinatorLimits, AForceBeyondItsBoundStopsTheTestOnThatFeedback) {
  // The spring holds 7008 N at 10 mm: a 6000 N bound is crossed by the first measurement.
  const auto s = scenario_with_limits("{max_force_n: 6000}");
  const TestRun run = run_test(s, {}, false);
  EXPECT_EQ(run.outcome, StepOutcome::kLimit);
  EXPECT_EQ(run.limit_stop.kind, LimitStop::Kind::kForce);
  EXPECT_NEAR(run.limit_stop.value, 700.8e3 * 0.01, 50.0);
  // Within the bounds nothing stops: the same test with room to spare completes.
  const TestRun free =
      run_test(scenario_with_limits("{max_stroke_m: 0.011, max_increment_m: 0.0002, max_force_n: 8000}"), {}, false);
  EXPECT_EQ(free.outcome, StepOutcome::kOk);
}

TEST(CoordinatorLimits, AnUnknownOrNonPositiveLimitIsNamedWithItsKey) {
  EXPECT_THROW(
      {
        try {
          scenario_with_limits("{max_strok_m: 0.01}");
        } catch (const std::exception& e) {
          EXPECT_NE(std::string(e.what()).find("experimental[0].limits.max_strok_m"), std::string::npos) << e.what();
          throw;
        }
      },
      std::exception);
  EXPECT_THROW(scenario_with_limits("{max_force_n: -1}"), std::exception);
}

}  // namespace
}  // namespace rpsd::coordinator
