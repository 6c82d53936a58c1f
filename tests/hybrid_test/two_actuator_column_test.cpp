// A whole two-actuator column test (translation and rotation of the column top, a coupled 2x2
// column stiffness) against results derived here, not by the code: in linear geometry on
// perfect actuators it is the coupled system M x'' + (K_N + K_column) x = 0, whose exact free
// vibration follows from its modes; the actuators' strokes are s1 = x, s2 = x - L θ; their load
// cells carry J^-T K_column u; and the worked example's rehearsal on servo-hydraulic actuators
// shows them pushing against each other while it follows its perfect-actuator reference.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "../servo/paper_rig.h"
#include "kept_records_run.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/hybrid_test/setup_plan.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::hybrid_test {
namespace {

constexpr double kL = 0.5;  // m: actuator 2 above actuator 1 (distance_between_actuators_m)

TestConfig load(const char* path) {
  return std::get<TestConfig>(scenarios::load_study(testing::source_dir() / path).study);
}

TEST(TwoActuatorColumn, LinearOnPerfectActuatorsItIsTheCoupledSystemsExactFreeVibration) {
  const TestConfig t = load("tests/hybrid_test/data/two-actuator-column-free-vibration.yaml");
  const TestRun r = run_keeping_records(t);
  ASSERT_EQ(r.outcome, coordinator::StepOutcome::kOk);
  ASSERT_EQ(r.records.size(), 4096u);

  // The structure written out: the numerical part plus the column at the column top's DOFs.
  Eigen::Matrix3d m = Eigen::Vector3d(12000.0, 40000.0, 15000.0).asDiagonal(), k;
  k << 0.5e6 + 1.0e6, 0.75e6, -0.5e6,  //
      0.75e6, 1.0e6 + 0.75e6, 0.0,     //
      -0.5e6, 0.0, 0.5e6;
  const Eigen::Matrix2d column = (Eigen::Matrix2d() << 1.0e6, 0.75e6, 0.75e6, 0.75e6).finished();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> modes(k, m);
  const Eigen::Vector3d x0(0.004, -0.003, 0.006);
  const Eigen::Vector3d q0 = modes.eigenvectors().transpose() * m * x0;  // mass-normalised modes

  double worst = 0.0, worst_stroke = 0.0, worst_force = 0.0, peak_force = 0.0;
  for (const auto& s : r.records) {
    Eigen::Vector3d exact = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) {
      exact += modes.eigenvectors().col(i) * q0[i] * std::cos(std::sqrt(modes.eigenvalues()[i]) * s.time_s);
    }
    for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(s.displacement_m[d] - exact[d]));
    // The actuators' strokes by the setup's closed form, from the DOFs the test measured.
    const double x = s.dof_measured_m[0], theta = s.dof_measured_m[1];
    worst_stroke =
        std::max({worst_stroke, std::abs(s.measured_m[0] - x), std::abs(s.measured_m[1] - (x - kL * theta))});
    // Jᵀ f = F with J = [[1, 0], [1, -L]]: f2 = -M / L, f1 = F_x - f2.
    const Eigen::Vector2d f = column * Eigen::Vector2d(x, theta);
    const double f2 = -f[1] / kL, f1 = f[0] - f2;
    worst_force = std::max({worst_force, std::abs(s.measured_force_n[0] - f1), std::abs(s.measured_force_n[1] - f2)});
    peak_force = std::max({peak_force, std::abs(f1), std::abs(f2)});
    // The DOF view is the column's force at the measured DOFs.
    EXPECT_NEAR(s.dof_force_n[0], s.measured_force_n[0] + s.measured_force_n[1], 1e-9 * peak_force + 1e-9);
  }
  // Central difference at 1024 Hz: a relative period error of (ω Δt)² / 24 ≈ 6e-6 at the
  // highest mode (1.94 Hz), 4e-4 rad of phase after 4 s: well inside 1e-3 of the 6 mm start.
  EXPECT_LT(worst, 1e-3 * 0.006);
  EXPECT_LT(worst_stroke, 1e-12);
  // The simulated column loads each actuator with the force of the strokes it measured one
  // control period before (docs/coupled-specimens.md): within ω Δt ≈ 1.2 % of the peak.
  EXPECT_LT(worst_force, 0.02 * peak_force);
}

TEST(TwoActuatorColumn, TheRehearsalFollowsItsReferenceWhileTheActuatorsPushAgainstEachOther) {
  TestConfig t = load("examples/scenarios/two-actuator-column.yaml");
  const TestRun test = run_keeping_records(t);
  ASSERT_EQ(test.outcome, coordinator::StepOutcome::kOk);
  TestAssembly reference_assembly(t, {{}, true, true, {}});
  const TestRun reference = reference_assembly.finish(reference_assembly.run({}, {}));
  ASSERT_EQ(reference.records.size(), test.records.size());
  double error2 = 0.0, reference2 = 0.0, opposed_n = 0.0, peak_dof_force = 0.0, peak_actuator_force = 0.0;
  for (std::size_t n = 0; n < test.records.size(); ++n) {
    const auto& s = test.records[n];
    error2 += std::pow(s.displacement_m[0] - reference.records[n].displacement_m[0], 2);
    reference2 += std::pow(reference.records[n].displacement_m[0], 2);
    if (s.measured_force_n[0] * s.measured_force_n[1] < 0.0) {
      opposed_n = std::max(opposed_n, std::min(std::abs(s.measured_force_n[0]), std::abs(s.measured_force_n[1])));
    }
    peak_dof_force = std::max(peak_dof_force, std::abs(s.dof_force_n[0]));
    peak_actuator_force =
        std::max({peak_actuator_force, std::abs(s.measured_force_n[0]), std::abs(s.measured_force_n[1])});
  }
  // The column top follows its reference (J4 of the example: about 20 %, the actuators' lag
  // and their loading beam's inertia), and at times the two actuators push against each
  // other by kilonewtons, each carrying more than the column's whole shear.
  EXPECT_LT(std::sqrt(error2 / reference2), 0.3);
  EXPECT_GT(opposed_n, 1.0e3);
  EXPECT_GT(peak_actuator_force, 1.5 * peak_dof_force);
}

TEST(TwoActuatorColumn, EachActuatorsForceGuardPredictsWithItsShareOfTheCoupledColumn) {
  // J = [[1, 0], [1, -L]] at rest, J^-1 = [[1, 0], [2, -2]]: the actuators' stiffness
  // J^-T K J^-1 = [[7.0, -4.5], [-4.5, 3.0]] MN/m for the column's K, coupling included
  // (a DOF-diagonal K would give 4.0 and 3.0).
  const TestConfig t = load("examples/scenarios/two-actuator-column.yaml");
  const SetupPlan plan = plan_setups(t, Eigen::Vector3d::Zero().head(2), 1.0 / 1024.0, false);
  EXPECT_NEAR(plan.stiffness_estimate_n_per_m[0], 7.0e6, 1.0);
  EXPECT_NEAR(plan.stiffness_estimate_n_per_m[1], 3.0e6, 1.0);
}

TEST(TwoActuatorColumn, ADofsRateStatedPerSecondActsPerControlPeriod) {
  // 2 mrad/s on the rotation: 1.95e-6 rad per period at 1024 Hz, which the record's rotation
  // passes early on; the run stops on the DOF, before its command leaves.
  TestConfig t = std::get<TestConfig>(
      scenarios::load_study(testing::source_dir() / "examples/scenarios/two-actuator-column.yaml",
                            {scenarios::parse_override("experimental.1.limits={max_rotation_rate_rad_per_s: 0.002}")})
          .study);
  const TestRun r = run_keeping_records(t);
  ASSERT_EQ(r.outcome, coordinator::StepOutcome::kLimit);
  EXPECT_EQ(r.limit_stop.kind, coordinator::LimitStop::Kind::kIncrement);
  EXPECT_EQ(std::string(r.limit_stop.name.data()), "site 1 DOF rotation");
  EXPECT_DOUBLE_EQ(r.limit_stop.bound, 0.002 / 1024.0);
}

}  // namespace
}  // namespace rpsd::hybrid_test
