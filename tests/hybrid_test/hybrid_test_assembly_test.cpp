// Whole-test runs from scenarios against exact solutions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../servo/paper_rig.h"
#include "rpsd/ground_motion/response_spectrum.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::hybrid_test {
namespace {

TEST(TestRunner, PerfectActuatorMatchesTheExactPiecewiseLinearSolutionOfTheRecord) {
  // The El Centro SDOF scenario with a perfect actuator is plain integration of
  // m x'' + c x' + k x = -m a_g; the exact solution for the piecewise-linear record is the
  // Nigam-Jennings recurrence. Peak displacements must agree to 0.5 %.
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml");
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  ASSERT_TRUE(scenario.ground_motion.has_value());
  const TestRun run = run_test(scenario, {}, true);
  ASSERT_EQ(run.outcome, coordinator::StepOutcome::kOk);
  double peak = 0.0;
  for (const auto& r : run.records) peak = std::max(peak, std::abs(r.displacement_m[0]));

  ground_motion::GroundMotionRecord record;
  record.dt_s = scenario.ground_motion->dt_s;
  record.acceleration_m_per_s2 = scenario.ground_motion->acceleration_m_per_s2;
  const double omega = std::sqrt(700.8e3 / 7080.0);
  const auto exact = ground_motion::sdof_response_piecewise_linear(record, omega, 0.011);
  double exact_peak = 0.0;
  for (double u : exact) exact_peak = std::max(exact_peak, std::abs(u));
  EXPECT_NEAR(peak / exact_peak, 1.0, 0.005);
  RecordProperty("peak_ratio", std::to_string(peak / exact_peak));
}

TEST(TestRunner, EveryRecordedStepIsKeptWhenRunningAsFastAsPossible) {
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/rths-benchmark-case1.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 5}")});
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const TestRun run = run_test(scenario, {}, false);
  EXPECT_EQ(run.dropped_records, 0u);
  EXPECT_EQ(static_cast<std::int64_t>(run.records.size()), run.steps_planned);
  // The benchmark plant with adaptive compensation tracks to a fraction of a percent.
  const coordinator::Criteria c = evaluate(scenario, run, run_test(scenario, {}, true));
  EXPECT_LT(c.channels[0].j2_rms_tracking_error_percent, 2.0);
  EXPECT_EQ(c.dofs.size(), 3u);
}

TEST(TestRunner, AnInProcessSitesRoundTripIsCountedOnEveryStepAsZero) {
  // In process the command is answered in the same call: every step's round trip is 0 s, and
  // the site's histogram (summary.json's timing) counts each one.
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 1}")});
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const TestRun run = run_test(scenario, {}, false);
  ASSERT_EQ(run.outcome, coordinator::StepOutcome::kOk);
  ASSERT_GT(run.steps, 0);
  ASSERT_EQ(run.timing.sites.size(), 1u);
  const realtime::LatencySummary& round_trip = run.timing.sites[0].round_trip;
  EXPECT_EQ(round_trip.count, run.steps);
  EXPECT_EQ(round_trip.max_s, 0.0);
  EXPECT_EQ(round_trip.mean_s, 0.0);
  EXPECT_EQ(round_trip.p99_s, 0.0);  // a bin's edge bounded by the exact maximum
}

TEST(TestRunner, StepByStepAnInProcessSitesRoundTripsAreCountedAsByRun) {
  // TestAssembly::step() counts an in-process site's 0 s round trips and adds them to its
  // histogram at finish(): the summary counts every step, as run()'s does.
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 1}")});
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  TestAssembly test(scenario, {});
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
  for (std::int64_t n = 0; n < test.steps_planned() && outcome == coordinator::StepOutcome::kOk; ++n)
    outcome = test.step();
  ASSERT_EQ(outcome, coordinator::StepOutcome::kOk);
  const TestRun run = test.finish(outcome);
  ASSERT_GT(run.steps, 0);
  ASSERT_EQ(run.timing.sites.size(), 1u);
  EXPECT_EQ(run.timing.sites[0].round_trip.count, run.steps);
  EXPECT_EQ(run.timing.sites[0].round_trip.max_s, 0.0);
  EXPECT_EQ(run.timing.sites[0].round_trip.p50_s, 0.0);
}

void expect_same(double a, double b, const char* what) {
  if (std::isnan(a) || std::isnan(b)) {
    EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << what;
  } else {
    EXPECT_EQ(a, b) << what;
  }
}

TEST(TestRunner, CriteriaComputedAsTheTestRunsEqualThoseFromKeptRecordsBitForBit) {
  // rpsd run evaluates the test and its reference step by step without keeping them (memory
  // stays flat over long records); the numbers must be those of the whole kept records.
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 6}")});
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const EvaluatedTest streamed = run_test_and_reference(scenario, {}, {});
  const TestRun test = run_test(scenario, {}, false), reference = run_test(scenario, {}, true);
  const coordinator::Criteria kept = evaluate(scenario, test, reference);
  EXPECT_TRUE(streamed.test.records.empty());
  EXPECT_EQ(streamed.test.steps, test.steps_planned);
  EXPECT_EQ(streamed.reference.steps, test.steps_planned);
  EXPECT_EQ(static_cast<std::int64_t>(test.records.size()), test.steps);
  ASSERT_EQ(streamed.criteria.channels.size(), 1u);
  ASSERT_EQ(streamed.criteria.dofs.size(), 1u);
  const auto& a = streamed.criteria.channels[0];
  const auto& b = kept.channels[0];
  EXPECT_TRUE(std::isfinite(a.j1_tracking_delay_ms));
  expect_same(a.j1_tracking_delay_ms, b.j1_tracking_delay_ms, "J1");
  expect_same(a.j2_rms_tracking_error_percent, b.j2_rms_tracking_error_percent, "J2");
  expect_same(a.j3_peak_tracking_error_percent, b.j3_peak_tracking_error_percent, "J3");
  expect_same(a.final_tracking_indicator_m2, b.final_tracking_indicator_m2, "TI");
  const auto& x = streamed.criteria.dofs[0];
  const auto& y = kept.dofs[0];
  expect_same(x.rms_error_percent, y.rms_error_percent, "J4");
  expect_same(x.peak_error_percent, y.peak_error_percent, "J7");
  expect_same(x.peak_displacement_m, y.peak_displacement_m, "peak");
  expect_same(x.reference_peak_displacement_m, y.reference_peak_displacement_m, "reference peak");
  expect_same(streamed.criteria.energy_error_j, kept.energy_error_j, "energy");
  // And the channel criteria of the Figure 8 study's path agree too.
  const coordinator::ChannelCriteria direct = coordinator::channel_criteria(test.records, 0, scenario.control_rate_hz);
  expect_same(direct.j1_tracking_delay_ms, b.j1_tracking_delay_ms, "J1 (coordinator::channel_criteria)");
  expect_same(direct.j2_rms_tracking_error_percent, b.j2_rms_tracking_error_percent,
              "J2 (coordinator::channel_criteria)");
}

}  // namespace
}  // namespace rpsd::hybrid_test
