// Natural frequencies and Rayleigh damping checked against closed forms and published values.

#include "reference_models.h"
#include "rpsd/substructure/damping.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/substructure/modal.h"
#include "rpsd/substructure/rayleigh.h"

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>

namespace rpsd::substructure {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Rayleigh, HandComputedEqualRatios) {
  // ζ = 5 % at 10 and 30 rad/s: a0 = 2ζ ω1 ω2/(ω1+ω2) = 0.75 1/s, a1 = 2ζ/(ω1+ω2) = 0.0025 s.
  const RayleighCoefficients c = rayleigh_from_frequencies(10.0, 30.0, 0.05, 0.05);
  EXPECT_NEAR(c.a0_per_s, 0.75, 1e-15);
  EXPECT_NEAR(c.a1_s, 0.0025, 1e-18);
  // Between the anchors the ratio dips; its minimum is at ω = √(a0/a1) = √300 rad/s.
  EXPECT_NEAR(rayleigh_damping_ratio(c, std::sqrt(300.0)), std::sqrt(0.75 * 0.0025), 1e-15);
}

TEST(Rayleigh, ReproducesTwoDifferentTargetRatiosExactly) {
  const double wa = 5.0, wb = 40.0, za = 0.02, zb = 0.05;
  const RayleighCoefficients c = rayleigh_from_frequencies(wa, wb, za, zb);
  EXPECT_NEAR(rayleigh_damping_ratio(c, wa), za, 1e-15);
  EXPECT_NEAR(rayleigh_damping_ratio(c, wb), zb, 1e-15);
  // Anchors given in reverse order give the same coefficients.
  const RayleighCoefficients r = rayleigh_from_frequencies(wb, wa, zb, za);
  EXPECT_NEAR(r.a0_per_s, c.a0_per_s, 1e-14);
  EXPECT_NEAR(r.a1_s, c.a1_s, 1e-18);
}

TEST(Rayleigh, RejectsBadAnchors) {
  EXPECT_THROW((void)rayleigh_from_frequencies(10.0, 10.0, 0.05, 0.05), std::invalid_argument);
  EXPECT_THROW((void)rayleigh_from_frequencies(0.0, 10.0, 0.05, 0.05), std::invalid_argument);
  EXPECT_THROW((void)rayleigh_from_frequencies(1.0, 10.0, -0.01, 0.05), std::invalid_argument);
  // 10 % at 1 rad/s and 0.01 % at 100 rad/s needs a1 = 2 (0.01 − 0.1) / 9999 < 0
  // (negative damping at high frequency).
  try {
    (void)rayleigh_from_frequencies(1.0, 100.0, 0.10, 0.0001);
    FAIL() << "expected a throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("negative coefficient"), std::string::npos) << e.what();
  }
}

TEST(Modal, BenchmarkCase1Frequencies) {
  const linalg::StructuralMatrix M(Eigen::MatrixXd(test::benchmark_case1_mass()));
  const linalg::StructuralMatrix K(Eigen::MatrixXd(test::benchmark_case1_stiffness()));
  const Eigen::VectorXd w = natural_frequencies_rad_s(M, K);
  ASSERT_EQ(w.size(), 3);
  for (int i = 0; i < 3; ++i) {
    // The sheet gives three decimals: the frequency must round to the published value.
    EXPECT_NEAR(w[i] / (2.0 * kPi), test::kBenchmarkCase1FrequenciesHz[i], 5e-4) << "mode " << i + 1;
  }
  // Same result through sparse storage.
  const Eigen::VectorXd ws = natural_frequencies_rad_s(M.converted(linalg::MatrixStorage::kSparse),
                                                       K.converted(linalg::MatrixStorage::kSparse));
  EXPECT_LT((ws - w).cwiseAbs().maxCoeff(), 1e-9 * w.maxCoeff());
}

TEST(Modal, UniformShearBuildingClosedForm) {
  // N equal floors m and stories k: ω_j = 2 √(k/m) sin((2j − 1) π / (2 (2N + 1))).
  const int N = 10;
  const double m = 2.0e4, k = 3.0e7;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  for (int i = 0; i < N; ++i) {
    K(i, i) = (i + 1 < N) ? 2.0 * k : k;
    if (i + 1 < N) K(i, i + 1) = K(i + 1, i) = -k;
  }
  const ModalSolution modal = modal_analysis(
      linalg::StructuralMatrix(Eigen::MatrixXd(m * Eigen::MatrixXd::Identity(N, N))), linalg::StructuralMatrix(K));
  for (int j = 1; j <= N; ++j) {
    const double exact = 2.0 * std::sqrt(k / m) * std::sin((2 * j - 1) * kPi / (2.0 * (2 * N + 1)));
    EXPECT_NEAR(modal.omega_rad_s[j - 1], exact, 1e-10 * exact) << "mode " << j;
  }
  // Mass-normalised modes: Φᵀ M Φ = I.
  const Eigen::MatrixXd G = modal.modes.transpose() * (m * modal.modes);
  EXPECT_LT((G - Eigen::MatrixXd::Identity(N, N)).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Modal, RejectsBadMatrices) {
  const linalg::StructuralMatrix M(Eigen::MatrixXd(Eigen::MatrixXd::Identity(2, 2)));
  Eigen::MatrixXd Kneg(2, 2);
  Kneg << -1.0, 0.0, 0.0, 2.0;  // one negative eigenvalue
  EXPECT_THROW((void)natural_frequencies_rad_s(M, linalg::StructuralMatrix(Kneg)), std::invalid_argument);
  EXPECT_THROW(
      (void)natural_frequencies_rad_s(M, linalg::StructuralMatrix(Eigen::MatrixXd(Eigen::MatrixXd::Identity(3, 3)))),
      std::invalid_argument);
}

// Modal damping ratios of a built C: ζ_k = φ_kᵀ C φ_k / (2 ω_k) for mass-normalised φ_k,
// computed here with Eigen's solver directly, independent of the library's modal code.
struct ModalProjection {
  Eigen::VectorXd omega;
  Eigen::MatrixXd phiT_C_phi;
};
ModalProjection modal_damping(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, const Eigen::MatrixXd& C) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  return {es.eigenvalues().cwiseSqrt(), es.eigenvectors().transpose() * C * es.eigenvectors()};
}

TEST(Rayleigh, BenchmarkCase1ModalDampingMatchesAnalyticCurve) {
  LinearMdofParameters cfg;
  cfg.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd(test::benchmark_case1_mass()));
  cfg.stiffness_n_per_m = linalg::StructuralMatrix(Eigen::MatrixXd(test::benchmark_case1_stiffness()));
  cfg.damping = RayleighFromModes{1, 2, 0.05, 0.05};  // ζ = 5 % as in the benchmark
  LinearMdofModel model;
  model.configure(cfg);

  const ModalProjection md =
      modal_damping(test::benchmark_case1_mass(), test::benchmark_case1_stiffness(), model.damping().dense());
  const double w1 = md.omega[0], w2 = md.omega[1], w3 = md.omega[2];
  // Closed-form coefficients for equal ratios, from the test's own frequencies.
  const double a0 = 2.0 * 0.05 * w1 * w2 / (w1 + w2), a1 = 2.0 * 0.05 / (w1 + w2);
  ASSERT_TRUE(model.rayleigh().has_value());
  EXPECT_NEAR(model.rayleigh()->a0_per_s, a0, 1e-10 * a0);
  EXPECT_NEAR(model.rayleigh()->a1_s, a1, 1e-10 * a1);
  EXPECT_NEAR(md.phiT_C_phi(0, 0) / (2.0 * w1), 0.05, 1e-12);
  EXPECT_NEAR(md.phiT_C_phi(1, 1) / (2.0 * w2), 0.05, 1e-12);
  EXPECT_NEAR(md.phiT_C_phi(2, 2) / (2.0 * w3), a0 / (2.0 * w3) + a1 * w3 / 2.0, 1e-12);
  EXPECT_GT(md.phiT_C_phi(2, 2) / (2.0 * w3), 0.05);  // above the anchors ζ grows with ω
  // Rayleigh damping is classical: it does not couple the modes.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j) {
        EXPECT_NEAR(md.phiT_C_phi(i, j), 0.0, 1e-10 * md.phiT_C_phi(2, 2));
      }
}

TEST(Rayleigh, EveryModeOfATenStoryBuildingFollowsTheCurve) {
  // Anchors at modes 1 and 3 with different ratios; check all ten modes, dense and sparse.
  const int N = 10;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(N, N), K = Eigen::MatrixXd::Zero(N, N);
  for (int i = 0; i < N; ++i) {
    M(i, i) = 1.0e4 * (1.0 + 0.1 * i);
    const double k_here = 2.0e7 * (N - i), k_above = i + 1 < N ? 2.0e7 * (N - i - 1) : 0.0;
    K(i, i) = k_here + k_above;
    if (i + 1 < N) K(i, i + 1) = K(i + 1, i) = -k_above;
  }
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    LinearMdofParameters cfg;
    cfg.mass_kg = linalg::StructuralMatrix(M).converted(storage);
    cfg.stiffness_n_per_m = linalg::StructuralMatrix(K).converted(storage);
    cfg.damping = RayleighFromModes{1, 3, 0.02, 0.04};
    LinearMdofModel model;
    model.configure(cfg);
    EXPECT_EQ(model.damping().is_sparse(), storage == linalg::MatrixStorage::kSparse);
    const ModalProjection md = modal_damping(M, K, model.damping().to_dense());
    const double wa = md.omega[0], wb = md.omega[2];
    const double a1 = 2.0 * (0.04 * wb - 0.02 * wa) / (wb * wb - wa * wa);
    const double a0 = 2.0 * wa * wb * (0.02 * wb - 0.04 * wa) / (wb * wb - wa * wa);
    EXPECT_NEAR(md.phiT_C_phi(0, 0) / (2.0 * wa), 0.02, 1e-12);
    EXPECT_NEAR(md.phiT_C_phi(2, 2) / (2.0 * wb), 0.04, 1e-12);
    for (int k = 0; k < N; ++k) {
      const double w = md.omega[k];
      EXPECT_NEAR(md.phiT_C_phi(k, k) / (2.0 * w), a0 / (2.0 * w) + a1 * w / 2.0, 1e-11) << "mode " << k + 1;
    }
  }
}

TEST(Rayleigh, FromGivenFrequenciesAndCoefficients) {
  const linalg::StructuralMatrix M(Eigen::MatrixXd(test::benchmark_case1_mass()));
  const linalg::StructuralMatrix K(Eigen::MatrixXd(test::benchmark_case1_stiffness()));
  const BuiltDamping b = build_damping(RayleighFromFrequencies{10.0, 30.0, 0.05, 0.05}, M, K, "");
  ASSERT_TRUE(b.rayleigh.has_value());
  EXPECT_NEAR(b.rayleigh->a0_per_s, 0.75, 1e-15);
  EXPECT_NEAR(b.rayleigh->a1_s, 0.0025, 1e-18);
  const Eigen::MatrixXd expected = 0.75 * M.dense() + 0.0025 * K.dense();
  EXPECT_LT((b.c.dense() - expected).cwiseAbs().maxCoeff(), 1e-9);
  const BuiltDamping c = build_damping(RayleighCoefficients{0.5, 0.001}, M, K, "");
  EXPECT_LT((c.c.dense() - (0.5 * M.dense() + 0.001 * K.dense())).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_THROW((void)build_damping(RayleighCoefficients{-0.5, 0.001}, M, K, ""), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::substructure
