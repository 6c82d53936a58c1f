// A specimen with mass and damping: the test (numerical part without them, the specimen's
// measured force k x + c x' + m a) and its perfect-actuator reference (the whole structure in
// the numerical part) must both be the whole SDOF, m = 1000 kg, c = 200 N s/m, k = 1e5 N/m,
// whose exact response to the piecewise-linear record is the Nigam-Jennings recurrence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../servo/paper_rig.h"
#include "rpsd/ground_motion/response_spectrum.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::hybrid_test {
namespace {

double peak_of(const TestRun& run) {
  double peak = 0.0;
  for (const auto& r : run.records) peak = std::max(peak, std::abs(r.displacement_m[0]));
  return peak;
}

TEST(SpecimenMass, TestAndReferenceAreTheWholeStructureUnderTheWholeMassesGroundLoad) {
  const auto file =
      scenarios::load_study(testing::source_dir() / "tests/hybrid_test/data/sdof-specimen-mass-and-damping.yaml");
  const auto& scenario = std::get<TestConfig>(file.study);
  ground_motion::GroundMotionRecord record;
  record.dt_s = scenario.ground_motion->dt_s;
  record.acceleration_m_per_s2 = scenario.ground_motion->acceleration_m_per_s2;
  const double omega = std::sqrt(1.0e5 / 1000.0), zeta = 200.0 / (2.0 * std::sqrt(1.0e5 * 1000.0));
  double exact_peak = 0.0;
  for (double u : ground_motion::sdof_response_piecewise_linear(record, omega, zeta))
    exact_peak = std::max(exact_peak, std::abs(u));
  // 30 % of the mass in the specimen: a part that kept it, or a ground load without it, would
  // be off by tens of percent. The reference is plain integration (0.5 %); the test adds the
  // actuator's 60 us and the inertial force's half period of lag (2 %).
  const TestRun reference = run_test(scenario, {}, true);
  ASSERT_EQ(reference.outcome, coordinator::StepOutcome::kOk);
  EXPECT_NEAR(peak_of(reference) / exact_peak, 1.0, 0.005);
  const TestRun test = run_test(scenario, {}, false);
  ASSERT_EQ(test.outcome, coordinator::StepOutcome::kOk);
  EXPECT_NEAR(peak_of(test) / exact_peak, 1.0, 0.02);
  RecordProperty("test_peak_ratio", std::to_string(peak_of(test) / exact_peak));
}

}  // namespace
}  // namespace rpsd::hybrid_test
