// The sparse eigen-solver (lowest_modes_sparse, Spectra) against closed forms and against the
// dense solver it stands in for on models too large for it.

#include "rpsd/substructure/modal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace rpsd::substructure {
namespace {

// A chain of springs k_i between masses m_i, the first spring to the ground; the last mass is
// free. `ground` false: no first spring (a rigid-body mode).
linalg::StructuralMatrix chain_stiffness(const std::vector<double>& k, bool ground = true) {
  const auto n = static_cast<Eigen::Index>(k.size());
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < n; ++i) {
    // Spring i joins mass i - 1 (the ground for i = 0) to mass i.
    if (i == 0 && !ground) continue;
    const double ki = k[static_cast<std::size_t>(i)];
    t.emplace_back(i, i, ki);
    if (i > 0) {
      t.emplace_back(i - 1, i - 1, ki);
      t.emplace_back(i, i - 1, -ki);
      t.emplace_back(i - 1, i, -ki);
    }
  }
  linalg::SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return linalg::StructuralMatrix(K);
}

// Fixed-free chain of n equal springs and masses: w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2n + 1))).
double chain_omega(int j, int n, double k, double m) {
  return 2.0 * std::sqrt(k / m) * std::sin((2.0 * j - 1.0) * std::numbers::pi / (2.0 * (2.0 * n + 1.0)));
}

TEST(SparseModal, ChainBeyondTheDenseLimitMatchesTheClosedForm) {
  const int n = 5000;
  const double k = 4.0e7, m = 2.0;
  const auto K = chain_stiffness(std::vector<double>(n, k));
  const auto M = linalg::StructuralMatrix::diagonal(Eigen::VectorXd::Constant(n, m));
  ASSERT_GT(n, kMaxDenseEigenDofs);
  const ModalSolution modes = lowest_modes(M, K, 8);
  ASSERT_EQ(modes.omega_rad_s.size(), 8);
  ASSERT_EQ(modes.modes.rows(), n);
  for (int j = 1; j <= 8; ++j) {
    EXPECT_NEAR(modes.omega_rad_s[j - 1] / chain_omega(j, n, k, m), 1.0, 1e-9) << "mode " << j;
    // Mass-normalised, and the mode shape of the chain: sin((2j - 1) pi i / (2n + 1)).
    const Eigen::VectorXd phi = modes.modes.col(j - 1);
    EXPECT_NEAR(m * phi.squaredNorm(), 1.0, 1e-9);
    const double a = std::sin((2.0 * j - 1.0) * std::numbers::pi * n / (2.0 * n + 1.0)) / phi[n - 1];
    for (int i : {1, n / 3, n / 2, n}) {
      EXPECT_NEAR(a * phi[i - 1], std::sin((2.0 * j - 1.0) * std::numbers::pi * i / (2.0 * n + 1.0)), 1e-6);
    }
  }
}

// Uneven masses and springs, coupled beyond neighbours: the sparse solver gives the dense one's
// lowest modes (frequencies and mass-normalised shapes, up to sign).
TEST(SparseModal, SmallModelAgreesWithTheDenseSolver) {
  const int n = 60;
  std::vector<double> k(n), m(n);
  for (int i = 0; i < n; ++i) {
    k[static_cast<std::size_t>(i)] = 1.0e6 * (1.0 + 0.37 * std::sin(1.3 * i));
    m[static_cast<std::size_t>(i)] = 500.0 * (1.0 + 0.5 * std::cos(0.7 * i));
  }
  linalg::SparseMatrix K = chain_stiffness(k).sparse();
  for (int i = 0; i + 3 < n; i += 5) {  // braces across three storeys
    const double kb = 2.0e5;
    K.coeffRef(i, i) += kb;
    K.coeffRef(i + 3, i + 3) += kb;
    K.coeffRef(i, i + 3) -= kb;
    K.coeffRef(i + 3, i) -= kb;
  }
  Eigen::VectorXd mass(n);
  for (int i = 0; i < n; ++i) mass[i] = m[static_cast<std::size_t>(i)];
  const linalg::StructuralMatrix KK(K), M = linalg::StructuralMatrix::diagonal(mass);
  const ModalSolution dense = modal_analysis(M, KK);
  const ModalSolution sparse = lowest_modes_sparse(M, KK, 6);
  ASSERT_EQ(sparse.omega_rad_s.size(), 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(sparse.omega_rad_s[j] / dense.omega_rad_s[j], 1.0, 1e-10) << "mode " << j + 1;
    const double overlap = sparse.modes.col(j).dot(mass.asDiagonal() * dense.modes.col(j));
    EXPECT_NEAR(std::abs(overlap), 1.0, 1e-8) << "mode " << j + 1;
  }
  // lowest_modes takes the dense path here, and keeps only what was asked for.
  const ModalSolution few = lowest_modes(M, KK, 4);
  ASSERT_EQ(few.omega_rad_s.size(), 4);
  EXPECT_EQ(few.omega_rad_s, dense.omega_rad_s.head(4));
}

TEST(SparseModal, RigidBodyModeIsZero) {
  const int n = 40;
  const double k = 1.0e6, m = 10.0;
  const auto K = chain_stiffness(std::vector<double>(n, k), false);
  const auto M = linalg::StructuralMatrix::diagonal(Eigen::VectorXd::Constant(n, m));
  const ModalSolution dense = modal_analysis(M, K);
  const ModalSolution sparse = lowest_modes_sparse(M, K, 3);
  // K - sigma M about a shift just below zero is ill-conditioned: some digits go.
  EXPECT_NEAR(sparse.omega_rad_s[0], 0.0, 1e-3);
  EXPECT_NEAR(sparse.omega_rad_s[1] / dense.omega_rad_s[1], 1.0, 1e-7);
  EXPECT_NEAR(sparse.omega_rad_s[2] / dense.omega_rad_s[2], 1.0, 1e-7);
}

TEST(SparseModal, RejectsWhatTheDenseSolverRejects) {
  const int n = 30;
  auto K = chain_stiffness(std::vector<double>(n, 1.0e6)).sparse();
  K.coeffRef(5, 5) = -3.0e6;  // a negative storey: K indefinite
  const auto M = linalg::StructuralMatrix::diagonal(Eigen::VectorXd::Constant(n, 1.0));
  EXPECT_THROW((void)lowest_modes_sparse(M, linalg::StructuralMatrix(K), 3), std::invalid_argument);
  EXPECT_THROW((void)modal_analysis(M, linalg::StructuralMatrix(K)), std::invalid_argument);
  const auto ok = chain_stiffness(std::vector<double>(n, 1.0e6));
  EXPECT_THROW((void)lowest_modes_sparse(M, ok, n), std::invalid_argument);  // count below the DOFs
  EXPECT_THROW((void)lowest_modes_sparse(M, ok, 0), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::substructure
