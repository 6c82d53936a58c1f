// The linear-solver layer: every storage solves to round-off, a banded model keeps its
// natural order, a renumbered one is reordered, and each integrator gives the same
// trajectory for the same model stored densely or sparsely.
#include "rpsd/integrators/factory.h"
#include "rpsd/integrators/symmetric_solver.h"
#include "rpsd/substructure/frame_model.h"
#include "run_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>

namespace rpsd::integrators::test {
namespace {

using substructure::make_frame_model;
using substructure::permuted;

void expect_solves(const linalg::StructuralMatrix& a) {
  SymmetricSolver solver;
  solver.factorize(a, "test matrix");
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  Eigen::VectorXd x(a.rows()), ax(a.rows());
  solver.solve(b, x);
  a.multiply(x, ax);
  EXPECT_LT((ax - b).norm(), 1e-10 * b.norm());
}

TEST(SymmetricSolver, SolvesEveryStorage) {
  const auto frame = make_frame_model(200, 100.0, true);
  const auto k = linalg::StructuralMatrix(frame.stiffness).compacted();
  const auto m = linalg::StructuralMatrix(frame.mass).compacted();
  const auto p = linalg::StructuralMatrix(permuted(frame).stiffness).compacted();
  ASSERT_EQ(k.storage(), linalg::MatrixStorage::kSparse);
  expect_solves(k);
  expect_solves(m);
  expect_solves(p);
  expect_solves(linalg::StructuralMatrix(Eigen::MatrixXd(frame.stiffness)).compacted());
  expect_solves(
      linalg::StructuralMatrix(Eigen::MatrixXd(Eigen::VectorXd::LinSpaced(5, 1, 2).asDiagonal())).compacted());
}

// A banded model uses the band solver (factor = n (b + 1)); a renumbered one is reordered
// (AMD) back to a factor of comparable size.
TEST(SymmetricSolver, BandOrReorderKeepsTheFactorSmall) {
  const auto frame = make_frame_model(600, 100.0);
  SymmetricSolver banded, renumbered;
  banded.factorize(linalg::StructuralMatrix(frame.stiffness).compacted(), "banded");
  renumbered.factorize(linalg::StructuralMatrix(permuted(frame).stiffness).compacted(), "renumbered");
  // Band 32: the natural-order factor has at most n * 33 entries whatever the numbering.
  EXPECT_LE(banded.factor_nonzeros(), 600 * 33);
  EXPECT_LE(renumbered.factor_nonzeros(), 2 * banded.factor_nonzeros());
}

TEST(SymmetricSolver, RejectsSingularMatrix) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Ones(3, 3);
  SymmetricSolver s;
  EXPECT_THROW(s.factorize(linalg::StructuralMatrix(a).compacted(), "all-ones"), std::invalid_argument);
}

// omega_max for the central-difference check: the Lanczos estimate on a sparse model
// (consistent mass) against the dense generalized eigensolver, and the Gershgorin bound.
TEST(MaxNaturalFrequency, LanczosMatchesDenseEigenvalues) {
  const auto frame = make_frame_model(500, 3000.0, true);
  const auto M = linalg::StructuralMatrix(frame.mass).compacted();
  const auto K = linalg::StructuralMatrix(frame.stiffness).compacted();
  SymmetricSolver ms;
  ms.factorize(M, "mass");
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(frame.stiffness),
                                                               Eigen::MatrixXd(frame.mass), Eigen::EigenvaluesOnly);
  const double exact = std::sqrt(es.eigenvalues().maxCoeff());
  const double lanczos = max_natural_frequency_rad_s(M, K, ms);
  EXPECT_GE(lanczos, exact * (1.0 - 1e-6));
  EXPECT_LE(lanczos, exact * 1.01);
  const auto lumped = make_frame_model(500, 3000.0, false);
  const double bound = frequency_upper_bound_rad_s(linalg::StructuralMatrix(lumped.mass).compacted(),
                                                   linalg::StructuralMatrix(lumped.stiffness).compacted());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> el(Eigen::MatrixXd(lumped.stiffness),
                                                               Eigen::MatrixXd(lumped.mass), Eigen::EigenvaluesOnly);
  EXPECT_GE(bound, std::sqrt(el.eigenvalues().maxCoeff()));
  EXPECT_LE(bound, 3000.0 * (1.0 + 1e-12));
}

// Central difference on a 2,000-DOF sparse model with consistent mass: the configure-time
// check rejects dt just above 2/omega_max and accepts dt just below.
TEST(MaxNaturalFrequency, CentralDifferenceCheckOnLargeSparseModel) {
  const auto frame = make_frame_model(2000, 3000.0, true);
  const auto m = StructuralMatrices::sparse(frame.mass, frame.damping, frame.stiffness);
  const auto M = linalg::StructuralMatrix(frame.mass).compacted();
  SymmetricSolver ms;
  ms.factorize(M, "mass");
  const double w = max_natural_frequency_rad_s(M, linalg::StructuralMatrix(frame.stiffness).compacted(), ms);
  auto cd = make_integrator(CentralDifferenceParameters{});
  EXPECT_THROW(cd->configure(m, 1.02 * 2.0 / w), std::invalid_argument);
  EXPECT_NO_THROW(cd->configure(m, 0.98 * 2.0 / w));
}

TEST(DenseAndSparse, GiveTheSameTrajectory) {
  const auto frame = make_frame_model(90, 2000.0, true);
  const Eigen::MatrixXd M = frame.mass, C = frame.damping, K = frame.stiffness;
  for (const IntegratorConfig& c :
       {IntegratorConfig{CentralDifferenceParameters{}}, IntegratorConfig{NewmarkParameters{}},
        IntegratorConfig{HhtAlphaParameters{}}, IntegratorConfig{GeneralizedAlphaParameters{}},
        IntegratorConfig{AlphaOsParameters{}}, IntegratorConfig{ChangParameters{}},
        IntegratorConfig{ChenRiclesParameters{}}, IntegratorConfig{KolayRiclesAlphaParameters{}}}) {
    auto dense = make_integrator(c);
    auto sparse = make_integrator(c);
    dense->configure(StructuralMatrices::dense(M, C, K), 1e-3);
    sparse->configure(StructuralMatrices::sparse(frame.mass, frame.damping, frame.stiffness), 1e-3);
    const Eigen::VectorXd d0 = Eigen::VectorXd::LinSpaced(90, 0.0, 1e-3), z = Eigen::VectorXd::Zero(90);
    dense->initialize(d0, z, K * d0, z);
    sparse->initialize(d0, z, K * d0, z);
    Eigen::VectorXd r(90);
    for (int n = 0; n < 200; ++n) {
      hybrid_step(*dense, K, z, r);
      hybrid_step(*sparse, frame.stiffness, z, r);
    }
    EXPECT_LT((dense->displacement() - sparse->displacement()).norm(), 1e-9 * dense->displacement().norm() + 1e-15)
        << integrator_name(c);
  }
}

}  // namespace
}  // namespace rpsd::integrators::test
