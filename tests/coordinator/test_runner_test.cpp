// Whole-test runs from scenarios against exact solutions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../servo/paper_rig.h"
#include "rpsd/coordinator/test_runner.h"
#include "rpsd/scenarios/ground_motion/response_spectrum.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {
namespace {

TEST(TestRunner, PerfectActuatorMatchesTheExactPiecewiseLinearSolutionOfTheRecord) {
  // The El Centro SDOF scenario with a perfect actuator is plain integration of
  // m x'' + c x' + k x = -m a_g; the exact solution for the piecewise-linear record is the
  // Nigam-Jennings recurrence. Peak displacements must agree to 0.5 %.
  const auto file = scenarios::load_study(testing::source_dir() / "scenarios/elcentro-sdof.yaml");
  const auto& scenario = std::get<scenarios::TestScenario>(file.study);
  ASSERT_TRUE(scenario.ground_motion.has_value());
  const TestRun run = run_test(scenario, {}, true);
  ASSERT_EQ(run.outcome, StepOutcome::kOk);
  double peak = 0.0;
  for (const auto& r : run.records) peak = std::max(peak, std::abs(r.displacement_m[0]));

  scenarios::ground_motion::GroundMotionRecord record;
  record.dt_s = scenario.ground_motion->dt_s;
  record.acceleration_m_per_s2 = scenario.ground_motion->acceleration_m_per_s2;
  const double omega = std::sqrt(700.8e3 / 7080.0);
  const auto exact = scenarios::ground_motion::sdof_response_piecewise_linear(record, omega, 0.011);
  double exact_peak = 0.0;
  for (double u : exact) exact_peak = std::max(exact_peak, std::abs(u));
  EXPECT_NEAR(peak / exact_peak, 1.0, 0.005);
  RecordProperty("peak_ratio", std::to_string(peak / exact_peak));
}

TEST(TestRunner, EveryRecordedStepIsKeptWhenRunningAsFastAsPossible) {
  const auto file = scenarios::load_study(testing::source_dir() / "scenarios/rths-benchmark-case1.yaml",
                                          {scenarios::parse_override("ground_motion.trim={end_s: 5}")});
  const auto& scenario = std::get<scenarios::TestScenario>(file.study);
  const TestRun run = run_test(scenario, {}, false);
  EXPECT_EQ(run.dropped_records, 0u);
  EXPECT_EQ(static_cast<std::int64_t>(run.records.size()), run.steps_planned);
  // The benchmark plant with adaptive compensation tracks to a fraction of a percent.
  const Criteria c = evaluate(scenario, run, run_test(scenario, {}, true));
  EXPECT_LT(c.channels[0].j2_rms_tracking_error_percent, 2.0);
  EXPECT_EQ(c.dofs.size(), 3u);
}

}  // namespace
}  // namespace rpsd::coordinator
