// The pre-test check against delay theory: the paper's SDOF on an ideal 5 ms delay. Without
// compensation the loop's measured delay is the plant's, and the predicted damping is the
// exact root of m s^2 + c s + k e^{-s tau} = 0, negative here (the test would grow: not
// ready). With third-order extrapolation over the same 5 ms the delay is gone and the
// structure keeps its own 1.1 %.
#include <gtest/gtest.h>

#include <cmath>

#include "../servo/paper_rig.h"
#include "rpsd/compensation/delay_theory.h"
#include "rpsd/coordinator/dry_run.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {
namespace {

scenarios::TestScenario sdof(std::vector<scenarios::Override> overrides) {
  const auto file = scenarios::load_study(testing::source_dir() / "tests/coordinator/data/sdof-free-vibration.yaml", overrides);
  return std::get<scenarios::TestScenario>(file.study);
}

TEST(DryRun, UncompensatedDelayGivesTheExactDdeRootAndIsNotReady) {
  const DryRunReport r = dry_run(sdof({scenarios::parse_override("compensation={kind: none}")}));
  ASSERT_EQ(r.modes.size(), 1u);
  const auto& mode = r.modes[0];
  EXPECT_NEAR(mode.frequency_hz, std::sqrt(700.8e3 / 7080.0) / (2.0 * M_PI), 1e-9);
  EXPECT_NEAR(mode.loop_gain, 1.0, 0.01);
  // The plant's 5 ms, and the half period of the hold between commands at 1024 Hz at most.
  EXPECT_NEAR(mode.loop_delay_ms, 5.0, 0.5);
  const compensation::DelayedOscillator oscillator{7080.0, 2.0 * 0.011 * std::sqrt(700.8e3 * 7080.0), 0.0, 700.8e3};
  const double exact = compensation::damping_ratio_of(compensation::dominant_root(oscillator, 1e-3 * mode.loop_delay_ms));
  EXPECT_NEAR(mode.predicted_damping_ratio, exact, 1e-4);
  EXPECT_LT(mode.predicted_damping_ratio, 0.0);
  EXPECT_FALSE(r.within_limits);
}

TEST(DryRun, CompensatedDelayKeepsTheStructuresDampingAndIsReady) {
  const DryRunReport r = dry_run(sdof({}));
  ASSERT_EQ(r.modes.size(), 1u);
  EXPECT_NEAR(r.modes[0].loop_delay_ms, 0.0, 0.3);
  EXPECT_NEAR(r.modes[0].predicted_damping_ratio, 0.011, 0.002);
  EXPECT_TRUE(r.within_limits);
  // The free vibration starts at 10 mm: the peak command and displacement are 10 mm.
  EXPECT_NEAR(r.channels[0].peak_displacement_m, 0.01, 1e-4);
  EXPECT_FALSE(r.channels[0].peak_valve_opening.has_value());  // an ideal delay has no valve
}

TEST(DryRun, PeaksBeyondTheLimitsAreNotReady) {
  auto s = sdof({});
  s.experimental[0].limits.max_force_n = 5000.0;  // the spring holds 7008 N at the start
  const DryRunReport limited = dry_run(s);
  EXPECT_FALSE(limited.within_limits);
  EXPECT_EQ(limited.outcome, StepOutcome::kLimit);
}

TEST(DryRun, TheServoModelReportsItsValveOpeningAndRouthMargin) {
  const auto file = scenarios::load_study(testing::source_dir() / "scenarios/two-site-bridge.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 2}")});
  const DryRunReport r = dry_run(std::get<scenarios::TestScenario>(file.study));
  ASSERT_TRUE(r.p_gain && r.max_stable_p_gain);
  EXPECT_LT(*r.p_gain, *r.max_stable_p_gain);
  for (const auto& c : r.channels) {
    ASSERT_TRUE(c.peak_valve_opening.has_value());
    EXPECT_GT(*c.peak_valve_opening, 0.0);
    EXPECT_LE(*c.peak_valve_opening, 1.0);
  }
  EXPECT_EQ(r.modes.size(), 3u);
}

}  // namespace
}  // namespace rpsd::coordinator
