// The pre-test check against delay theory: the paper's SDOF on an ideal 5 ms delay. Without
// compensation the loop's measured delay is the plant's, and the predicted damping is the
// exact root of m s^2 + c s + k e^{-s tau} = 0, negative here (the test would grow: not
// ready). With third-order extrapolation over the same 5 ms the delay is gone and the
// structure keeps its own 1.1 %.
#include <gtest/gtest.h>

#include <cmath>

#include "../servo/paper_rig.h"
#include "rpsd/compensation/delay_theory.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/studies/dry_run.h"

namespace rpsd::studies {
namespace {

hybrid_test::TestConfig sdof(std::vector<scenarios::Override> overrides) {
  const auto file =
      scenarios::load_study(testing::source_dir() / "tests/coordinator/data/sdof-free-vibration.yaml", overrides);
  return std::get<hybrid_test::TestConfig>(file.study);
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
  const double exact =
      compensation::damping_ratio_of(compensation::dominant_root(oscillator, 1e-3 * mode.loop_delay_ms));
  EXPECT_NEAR(mode.predicted_damping_ratio, exact, 1e-4);
  EXPECT_LT(mode.predicted_damping_ratio, 0.0);
  EXPECT_FALSE(r.within_limits);
}

// The telemetry's predicted effective damping is the dry run's lowest mode's, without a step.
TEST(DryRun, ThePredictionForTheTelemetryIsTheDryRunsLowestMode) {
  const auto uncompensated = sdof({scenarios::parse_override("compensation={kind: none}")});
  const double predicted = predicted_lowest_mode_damping(uncompensated);
  EXPECT_LT(predicted, 0.0);  // the 5 ms the compensator does not remove
  EXPECT_EQ(predicted, dry_run(uncompensated).modes[0].predicted_damping_ratio);
  EXPECT_NEAR(predicted_lowest_mode_damping(sdof({})), 0.011, 0.002);
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
  EXPECT_EQ(limited.outcome, coordinator::StepOutcome::kLimit);
}

// The node's own limits, the layer on the rig: a 10 mm free vibration passes a 25 mm stroke
// and fails a 5 mm one (at the node; the coordinator, without limits, runs to the end).
NodeLimits node_with(node::ChannelLimits limits) {
  NodeLimits node;
  node.name = "node-site-1.yaml";
  node.test_id = 1;
  node.site_id = 1;
  node.control_period_s = 1.0 / 2048.0;
  node.channels = {limits};
  return node;
}

TEST(DryRun, ChecksTheCommandsAgainstTheNodesOwnLimits) {
  node::ChannelLimits wide;
  wide.max_stroke_m = 0.025;
  const DryRunReport ok = dry_run(sdof({}), {node_with(wide)});
  ASSERT_TRUE(ok.channels[0].node.has_value());
  EXPECT_TRUE(ok.channels[0].node->within_limits);
  EXPECT_TRUE(ok.within_limits);
  // The node's velocity is its command change per its own period (here 1/2048 s).
  EXPECT_DOUBLE_EQ(ok.channels[0].node->peak_command_velocity_m_per_s, ok.channels[0].peak_increment_m * 2048.0);
  // A 10 mm swing at 1.58 Hz: at most 2 pi f x0 = 99 mm/s, in 1/1024 s steps.
  EXPECT_NEAR(ok.channels[0].peak_increment_m * 1024.0, 2.0 * M_PI * std::sqrt(700.8e3 / 7080.0) / (2.0 * M_PI) * 0.01,
              0.01);

  node::ChannelLimits narrow = wide;
  narrow.max_stroke_m = 0.005;
  const DryRunReport stroke = dry_run(sdof({}), {node_with(narrow)});
  EXPECT_EQ(stroke.outcome, coordinator::StepOutcome::kOk);  // the coordinator itself had no reason to stop
  EXPECT_FALSE(stroke.channels[0].node->within_limits);
  EXPECT_FALSE(stroke.within_limits);

  node::ChannelLimits slow = wide;
  slow.max_velocity_m_per_s = 0.1;  // 99 mm/s per 1/1024 s is 198 mm/s per the node's 1/2048 s
  EXPECT_FALSE(dry_run(sdof({}), {node_with(slow)}).within_limits);
}

TEST(DryRun, RefusesNodeFilesThatDoNotFitTheTest) {
  const auto s = sdof({});
  NodeLimits other_test = node_with({});
  other_test.test_id = 2;
  EXPECT_THROW(dry_run(s, {other_test}), std::invalid_argument);
  NodeLimits other_site = node_with({});
  other_site.site_id = 3;
  EXPECT_THROW(dry_run(s, {other_site}), std::invalid_argument);
  NodeLimits two_channels = node_with({});
  two_channels.channels.resize(2);
  EXPECT_THROW(dry_run(s, {two_channels}), std::invalid_argument);
  EXPECT_THROW(dry_run(s, {node_with({}), node_with({})}), std::invalid_argument);
}

TEST(DryRun, TheServoModelReportsItsValveOpeningAndRouthMargin) {
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/two-site-bridge.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 2}")});
  const DryRunReport r = dry_run(std::get<hybrid_test::TestConfig>(file.study));
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
}  // namespace rpsd::studies
