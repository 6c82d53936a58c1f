// The typed suite every scheme runs: closed-form SDOF responses, second-order
// convergence, stability, the RTHS benchmark building against modal superposition,
// and configure-time rejection of bad input.
#include "rpsd/integrators/amplification.h"
#include "rpsd/integrators/factory.h"
#include "run_helpers.h"
#include "scheme_traits.h"
#include "sdof_exact.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>
#include <vector>

namespace rpsd::integrators::test {
namespace {

using std::numbers::pi;

template <class T>
class EveryScheme : public ::testing::Test {};

TYPED_TEST_SUITE(EveryScheme, Schemes, SchemeNames);

// Max |x_n - x(t_n)| over [0, duration] for an SDOF with omega = 2 pi (T = 1 s).
double sdof_max_error(const IntegratorConfig& config, const SdofExact& exact, double dt, double duration,
                      double* peak = nullptr) {
  auto integrator = make_integrator(config);
  const double m = 2.0;
  const double k = m * exact.omega * exact.omega;
  const double c = 2.0 * exact.xi * m * exact.omega;
  integrator->configure(
      StructuralMatrices::dense(Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                                Eigen::MatrixXd::Constant(1, 1, k)),
      dt);
  auto force = [&](double t) { return Eigen::VectorXd::Constant(1, m * exact.p0 * std::sin(exact.omega_f * t)); };
  const Eigen::VectorXd d0 = Eigen::VectorXd::Constant(1, exact.x0);
  integrator->initialize(d0, Eigen::VectorXd::Constant(1, exact.v0), k * d0, force(0.0));
  const Eigen::MatrixXd kk = Eigen::MatrixXd::Constant(1, 1, k);
  Eigen::VectorXd r(1);
  const int steps = static_cast<int>(std::lround(duration / dt));
  double err = 0.0, pk = 0.0;
  for (int n = 1; n <= steps; ++n) {
    hybrid_step(*integrator, kk, force(n * dt), r);
    const double x = exact(n * dt);
    err = std::max(err, std::abs(integrator->displacement()(0) - x));
    pk = std::max(pk, std::abs(x));
  }
  if (peak) *peak = pk;
  return err;
}

// Damped free vibration, T = 1 s, dt = T/400, 3 s: within 0.2 % of the peak. The initial
// state (x0 = -2 xi v0 / omega) has a0 = 0: CR and KR-alpha carry a staggered velocity
// (v+ - v = dt alpha1 a), so a non-zero a0 costs them a first-order start-up error.
TYPED_TEST(EveryScheme, DampedFreeVibrationMatchesClosedForm) {
  const double w = 2.0 * pi, xi = 0.05, v0 = 0.1;
  const SdofExact exact{w, xi, -2.0 * xi * v0 / w, v0};
  double peak = 0.0;
  const double err = sdof_max_error(TypeParam::config(), exact, 1.0 / 400.0, 3.0, &peak);
  EXPECT_LT(err, 2e-3 * peak) << "max error " << err << " peak " << peak;
}

// Harmonic force at 0.8 of the natural frequency from rest plus initial conditions.
TYPED_TEST(EveryScheme, HarmonicResponseMatchesClosedForm) {
  const SdofExact exact{2.0 * pi, 0.02, 0.0, 0.0, 10.0, 0.8 * 2.0 * pi};
  double peak = 0.0;
  const double err = sdof_max_error(TypeParam::config(), exact, 1.0 / 400.0, 3.0, &peak);
  EXPECT_LT(err, 2e-3 * peak) << "max error " << err << " peak " << peak;
}

// Halving dt divides the global error by about 4 (second order).
TYPED_TEST(EveryScheme, SecondOrderConvergence) {
  const double w = 2.0 * pi, xi = 0.05, v0 = 0.05;  // a0 = 0, see above
  const SdofExact exact{w, xi, -2.0 * xi * v0 / w, v0, 5.0, 1.3 * 2.0 * pi};
  const double e1 = sdof_max_error(TypeParam::config(), exact, 1.0 / 200.0, 2.0);
  const double e2 = sdof_max_error(TypeParam::config(), exact, 1.0 / 400.0, 2.0);
  const double ratio = e1 / e2;
  EXPECT_GE(ratio, 3.5) << "errors " << e1 << " " << e2;
  EXPECT_LE(ratio, 4.5) << "errors " << e1 << " " << e2;
}

// Spectral radius <= 1 up to the scheme's limit (Omega = 100 when unconditional), for
// xi = 0 and 0.05; and above a finite limit the scheme is unstable.
TYPED_TEST(EveryScheme, StabilityLimit) {
  const double limit = TypeParam::stability_limit;
  for (double xi : {0.0, 0.05}) {
    const double top = std::isfinite(limit) ? limit * (1.0 - 1e-6) : 100.0;
    for (double w = 0.01; w <= top * (1.0 + 1e-12); w = std::min(w * 1.1, w < top ? top : 2 * top)) {
      const auto p = analyze_amplification(TypeParam::config(), w, xi);
      ASSERT_LE(p.spectral_radius, 1.0 + 1e-7) << "Omega " << w << " xi " << xi;
      if (w == top) break;
    }
  }
  const auto info = make_integrator(TypeParam::config())->info();
  if (std::isfinite(limit))
    EXPECT_NEAR(info.stability_limit_omega_dt, limit, 1e-12 * limit);
  else
    EXPECT_TRUE(std::isinf(info.stability_limit_omega_dt));
  if (std::isfinite(limit)) {
    EXPECT_NEAR(numerical_stability_limit(TypeParam::config(), 0.0, 10.0), limit, 1e-6 * limit);
    EXPECT_GT(analyze_amplification(TypeParam::config(), limit * 1.01, 0.0).spectral_radius, 1.0 + 1e-6);
  } else {
    EXPECT_TRUE(std::isinf(numerical_stability_limit(TypeParam::config(), 0.0, 100.0)));
  }
}

// The RTHS benchmark building, case 1 (Silva et al. 2020): M = 1000 I kg and K from the
// reference sheet; 5 % MODAL damping in every mode (C = M Phi diag(2 xi w) Phi^T M).
struct Building {
  Eigen::Matrix3d M, K, C, Phi;
  Eigen::Vector3d omega;
};
Building benchmark_building() {
  Building b;
  b.M = 1000.0 * Eigen::Matrix3d::Identity();
  b.K << 26054883.88, -23133938.88, 5937035.46,  //
      -23133938.88, 32560774.19, -14419970.78,   //
      5937035.46, -14419970.78, 9267275.51;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(b.K, b.M);
  b.omega = es.eigenvalues().cwiseSqrt();
  b.Phi = es.eigenvectors();  // mass-normalised: Phi^T M Phi = I
  const Eigen::Vector3d two_xi_w = 2.0 * 0.05 * b.omega;
  b.C = b.M * b.Phi * two_xi_w.asDiagonal() * b.Phi.transpose() * b.M;
  return b;
}

TEST(BenchmarkBuilding, NaturalFrequenciesMatchTheSheet) {
  const auto b = benchmark_building();
  EXPECT_NEAR(b.omega(0) / (2 * pi), 3.612, 1e-3);
  EXPECT_NEAR(b.omega(1) / (2 * pi), 15.997, 1e-3);
  EXPECT_NEAR(b.omega(2) / (2 * pi), 38.086, 1e-3);
}

// Harmonic ground acceleration a_g = A sin(w_g t) from rest, F = -M iota a_g, dt = 1/4096 s
// for 1 s; exact modal superposition of closed-form SDOF responses; every floor within
// 0.1 % of its peak.
TYPED_TEST(EveryScheme, BenchmarkBuildingMatchesModalSuperposition) {
  const auto b = benchmark_building();
  const double dt = 1.0 / 4096.0, A = 1.0, wg = 2.0 * pi * 5.0;
  const Eigen::Vector3d iota = Eigen::Vector3d::Ones();
  const Eigen::Vector3d gamma = b.Phi.transpose() * b.M * iota;
  auto integrator = make_integrator(TypeParam::config());
  integrator->configure(StructuralMatrices::dense(b.M, b.C, b.K), dt);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
  integrator->initialize(zero, zero, zero, zero);
  const Eigen::MatrixXd K = b.K;
  Eigen::VectorXd r(3), f(3);
  Eigen::Vector3d max_err = Eigen::Vector3d::Zero(), peak = Eigen::Vector3d::Zero();
  for (int n = 1; n <= 4096; ++n) {
    const double t = n * dt;
    f = -b.M * iota * A * std::sin(wg * t);
    hybrid_step(*integrator, K, f, r);
    Eigen::Vector3d q;
    for (int i = 0; i < 3; ++i) q(i) = SdofExact{b.omega(i), 0.05, 0.0, 0.0, -gamma(i) * A, wg}(t);
    const Eigen::Vector3d x = b.Phi * q;
    max_err = max_err.cwiseMax((integrator->displacement() - x).cwiseAbs());
    peak = peak.cwiseMax(x.cwiseAbs());
  }
  for (int i = 0; i < 3; ++i) EXPECT_LT(max_err(i), 1e-3 * peak(i)) << "floor " << i + 1 << " peak " << peak(i);
}

// Free vibration of the building at omega_max dt = 100 (unconditional schemes only): no
// growth. The peak strain energy over steps 1000-2000 stays below 1.5x the peak over steps
// 1-1000; an unstable step (spectral radius > 1) would grow it exponentially. (The size of
// the peak itself depends on the start: CR and KR-alpha, explicit in velocity, turn an
// initial velocity into a first step dt v0, large when omega dt = 100.)
TYPED_TEST(EveryScheme, LinearMdofDoesNotGrowAtOmegaDt100) {
  if (std::isfinite(TypeParam::stability_limit)) GTEST_SKIP() << "conditionally stable";
  const auto b = benchmark_building();
  const double dt = 100.0 / b.omega(2);
  auto integrator = make_integrator(TypeParam::config());
  integrator->configure(StructuralMatrices::dense(b.M, Eigen::Matrix3d::Zero(), b.K), dt);
  const Eigen::VectorXd d0 = Eigen::Vector3d(0.01, -0.02, 0.015);
  const Eigen::VectorXd v0 = Eigen::Vector3d(0.1, -0.2, 0.15);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
  const Eigen::MatrixXd K = b.K;
  integrator->initialize(d0, v0, K * d0, zero);
  Eigen::VectorXd r(3);
  double first = 0.0, second = 0.0;
  for (int n = 1; n <= 2000; ++n) {
    hybrid_step(*integrator, K, zero, r);
    const auto& d = integrator->displacement();
    ASSERT_TRUE(d.allFinite()) << "step " << n;
    (n <= 1000 ? first : second) = std::max(n <= 1000 ? first : second, 0.5 * d.dot(b.K * d));
  }
  EXPECT_GT(first, 0.0);
  EXPECT_LE(second, 1.5 * first);
}

TYPED_TEST(EveryScheme, RejectsBadInputAtConfigure) {
  using ::testing::HasSubstr;
  auto integrator = make_integrator(TypeParam::config());
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  auto expect_error = [&](const StructuralMatrices& m, double dt, const std::string& text) {
    try {
      integrator->configure(m, dt);
      ADD_FAILURE() << "no error, expected: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  Eigen::Matrix2d nonsym{{1.0, 0.1}, {0.0, 1.0}};
  Eigen::Matrix2d indefinite{{1.0, 2.0}, {2.0, 1.0}};
  expect_error(StructuralMatrices::dense(nonsym, 0 * I, I), 0.01, "mass matrix is not symmetric");
  expect_error(StructuralMatrices::dense(indefinite, 0 * I, I), 0.01, "mass matrix is not positive definite");
  expect_error(StructuralMatrices::dense(I, Eigen::Matrix3d::Zero(), I), 0.01, "damping matrix is 3x3, expected 2x2");
  expect_error(StructuralMatrices::dense(I, 0 * I, Eigen::MatrixXd::Identity(2, 3)), 0.01,
               "initial stiffness matrix is 2x3");
  expect_error(StructuralMatrices::dense(I, nonsym, I), 0.01, "damping matrix is not symmetric");
  expect_error(StructuralMatrices::dense(I, 0 * I, I), -0.01, "time step dt_s must be positive");
  const Eigen::SparseMatrix<double> s_nonsym = nonsym.sparseView();
  const Eigen::SparseMatrix<double> s_indef = indefinite.sparseView();
  const Eigen::SparseMatrix<double> s_eye = Eigen::MatrixXd(I).sparseView();
  expect_error(StructuralMatrices::sparse(s_nonsym, s_eye * 0.0, s_eye), 0.01, "mass matrix is not symmetric");
  expect_error(StructuralMatrices::sparse(s_indef, s_eye * 0.0, s_eye), 0.01, "mass matrix is not positive definite");
  // omega = 100 rad/s: dt beyond the limit must be rejected, dt inside accepted.
  const double limit = TypeParam::stability_limit;
  const Eigen::Matrix2d K = 1e4 * I;
  if (std::isfinite(limit)) {
    expect_error(StructuralMatrices::dense(I, 0 * I, K), 1.01 * limit / 100.0, "unstable time step");
    expect_error(StructuralMatrices::sparse(s_eye, s_eye * 0.0, Eigen::SparseMatrix<double>(K.sparseView())),
                 1.01 * limit / 100.0, "unstable time step");
  }
  EXPECT_NO_THROW(
      integrator->configure(StructuralMatrices::dense(I, 0 * I, K), std::isfinite(limit) ? 0.99 * limit / 100.0 : 1.0));
}

TEST(SchemeParameters, RejectsOutOfRangeValues) {
  using ::testing::HasSubstr;
  auto expect_error = [](const IntegratorConfig& c, const std::string& text) {
    try {
      (void)make_integrator(c);
      ADD_FAILURE() << "no error, expected: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  expect_error(HhtAlphaParameters{-0.5, {}}, "hht_alpha.alpha must be in [-1/3, 0]");
  expect_error(HhtAlphaParameters{0.1, {}}, "hht_alpha.alpha must be in [-1/3, 0]");
  expect_error(AlphaOsParameters{-0.4}, "alpha_os.alpha must be in [-1/3, 0]");
  expect_error(GeneralizedAlphaParameters{1.5, {}}, "rho_inf must be in [0, 1]");
  expect_error(KolayRiclesAlphaParameters{-0.1}, "rho_inf must be in [0, 1]");
  expect_error(NewmarkParameters{0.0, 0.5, {}}, "newmark.beta must be > 0");
  expect_error(NewmarkParameters{0.25, 0.4, {}}, "newmark.gamma must be >= 0.5");
  expect_error(NewmarkParameters{0.25, 0.5, {0, 1}}, "iterations must be in [1, 100]");
  expect_error(GeneralizedAlphaParameters{0.5, {2, 4}}, "poly_order must be 1, 2 or 3");
}

TEST(StepSequence, MisuseIsReportedNotThrown) {
  auto integrator = make_integrator(KolayRiclesAlphaParameters{});
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(1);
  EXPECT_EQ(integrator->begin_step(one), StepStatus::kNotInitialized);
  integrator->configure(
      StructuralMatrices::dense(Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Zero(1, 1), Eigen::MatrixXd::Ones(1, 1)),
      0.01);
  integrator->initialize(one, one * 0, one, one * 0);
  EXPECT_EQ(integrator->end_step(), StepStatus::kOutOfSequence);
  EXPECT_EQ(integrator->begin_step(Eigen::VectorXd::Ones(2)), StepStatus::kSizeMismatch);
  EXPECT_EQ(integrator->begin_step(one * NAN), StepStatus::kNonFiniteInput);
  EXPECT_EQ(integrator->begin_step(-one * INFINITY), StepStatus::kNonFiniteInput);
  EXPECT_EQ(integrator->begin_step(one), StepStatus::kOk);
  EXPECT_EQ(integrator->begin_step(one), StepStatus::kOutOfSequence);
  EXPECT_EQ(integrator->set_measured_restoring_force(one * NAN), StepStatus::kNonFiniteInput);
  EXPECT_EQ(integrator->set_measured_restoring_force(one * INFINITY), StepStatus::kNonFiniteInput);
  EXPECT_EQ(integrator->set_measured_restoring_force(one), StepStatus::kOk);
  EXPECT_EQ(integrator->set_measured_restoring_force(one), StepStatus::kOutOfSequence);
  EXPECT_EQ(integrator->end_step(), StepStatus::kOk);
  EXPECT_EQ(integrator->step(), 1);
  EXPECT_DOUBLE_EQ(integrator->time_s(), 0.01);
}

// Each per-step call compares its phase once and works out the error only on a wrong phase
// (Integrator::sequence_error): configured but not yet initialized is "not initialized" for
// every call, a call in another step phase "out of sequence", and neither changes the state.
TEST(StepSequence, EachCallInAWrongPhaseNamesWhyAndLeavesTheStepAlone) {
  auto integrator = make_integrator(CentralDifferenceParameters{});
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(1);
  integrator->configure(
      StructuralMatrices::dense(Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Zero(1, 1), Eigen::MatrixXd::Ones(1, 1)),
      0.01);
  EXPECT_EQ(integrator->begin_step(one), StepStatus::kNotInitialized);
  EXPECT_EQ(integrator->set_measured_restoring_force(one), StepStatus::kNotInitialized);
  EXPECT_EQ(integrator->end_step(), StepStatus::kNotInitialized);
  integrator->initialize(one, one * 0, one, one * 0);
  EXPECT_EQ(integrator->set_measured_restoring_force(one), StepStatus::kOutOfSequence);
  EXPECT_EQ(integrator->end_step(), StepStatus::kOutOfSequence);
  ASSERT_EQ(integrator->begin_step(one), StepStatus::kOk);
  EXPECT_EQ(integrator->end_step(), StepStatus::kOutOfSequence);
  ASSERT_EQ(integrator->set_measured_restoring_force(one), StepStatus::kOk);
  EXPECT_EQ(integrator->begin_step(one), StepStatus::kOutOfSequence);
  EXPECT_EQ(integrator->set_measured_restoring_force(one), StepStatus::kOutOfSequence);
  EXPECT_EQ(integrator->step(), 0);
  ASSERT_EQ(integrator->end_step(), StepStatus::kOk);
  EXPECT_EQ(integrator->step(), 1);
}

}  // namespace
}  // namespace rpsd::integrators::test

namespace rpsd::integrators::test {
namespace {

// Fixed-iteration implicit schemes on a linear SDOF with K0 = K: the Newton target is the
// implicit solution U*, and with polyOrder 1 the N commands are U_t + (i/N)(U* - U_t),
// evenly spaced, the last one U* itself. With order 2 they follow the parabola through
// U_{t-1}, U_t and U* at x = i/N.
TEST(FixedIterations, CommandsAreInterpolatedTowardsTheImplicitSolution) {
  for (int order : {1, 2}) {
    const int N = 4;
    auto integrator = make_integrator(HhtAlphaParameters{-0.1, {N, order}});
    const double k = 400.0;
    integrator->configure(
        StructuralMatrices::dense(Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 0.5),
                                  Eigen::MatrixXd::Constant(1, 1, k)),
        0.01);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
    integrator->initialize(Eigen::VectorXd::Constant(1, 0.01), zero, Eigen::VectorXd::Constant(1, k * 0.01), zero);
    Eigen::VectorXd r(1);
    const Eigen::MatrixXd K = Eigen::MatrixXd::Constant(1, 1, k);
    double u_prev = 0.01;
    for (int step = 0; step < 5; ++step) {
      const double u_t = integrator->displacement()(0);
      std::vector<double> commands;
      ASSERT_EQ(integrator->begin_step(zero), StepStatus::kOk);
      for (int i = 0; i < N; ++i) {
        commands.push_back(integrator->target_displacement()(0));
        r = K * integrator->target_displacement();
        integrator->set_measured_restoring_force(r);
      }
      integrator->end_step();
      const double u_star = integrator->displacement()(0);
      EXPECT_DOUBLE_EQ(commands.back(), u_star);
      for (int i = 1; i <= N; ++i) {
        const double x = static_cast<double>(i) / N;
        const double expected = order == 1 ? u_t + x * (u_star - u_t)
                                           : u_star * x * (x + 1) / 2 + u_t * (1 - x * x) + u_prev * x * (x - 1) / 2;
        EXPECT_NEAR(commands[static_cast<std::size_t>(i - 1)], expected, 1e-12)
            << "order " << order << " step " << step << " iteration " << i;
      }
      u_prev = u_t;
    }
  }
}

}  // namespace
}  // namespace rpsd::integrators::test
