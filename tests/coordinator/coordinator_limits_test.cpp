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
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

hybrid_test::TestConfig scenario_with_limits(const std::string& limits) {
  std::ifstream in(testing::source_dir() / "tests/coordinator/data/sdof-free-vibration.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string anchor = "    restoring_force: stiffness_times_displacement\n";
  text.replace(text.find(anchor), anchor.size(), anchor + "    limits: " + limits + "\n");
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
