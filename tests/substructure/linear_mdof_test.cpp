// Linear MDOF model: restoring force against the published stiffness, and configure-time
// validation messages.

#include "reference_models.h"
#include "rpsd/substructure/linear_mdof_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace rpsd::substructure {
namespace {

LinearMdofParameters benchmark_config(linalg::MatrixStorage storage) {
  LinearMdofParameters cfg;
  cfg.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd(test::benchmark_case1_mass())).converted(storage);
  cfg.stiffness_n_per_m =
      linalg::StructuralMatrix(Eigen::MatrixXd(test::benchmark_case1_stiffness())).converted(storage);
  return cfg;
}

// Runs configure and returns the exception message ("" if it did not throw).
std::string configure_error(const LinearMdofParameters& cfg) {
  LinearMdofModel m;
  try {
    m.configure(cfg);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

TEST(LinearMdof, RestoringForceIsThePublishedStiffnessColumns) {
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    LinearMdofModel model;
    model.configure(benchmark_config(storage));
    EXPECT_EQ(model.dofs(), 3);
    EXPECT_EQ(model.initial_stiffness().is_sparse(), storage == linalg::MatrixStorage::kSparse);
    Eigen::VectorXd r(3);
    model.restoring_force(Eigen::Vector3d(1.0, 0.0, 0.0), r);  // column 1 of K, N per m
    EXPECT_DOUBLE_EQ(r[0], 26054883.88);
    EXPECT_DOUBLE_EQ(r[1], -23133938.88);
    EXPECT_DOUBLE_EQ(r[2], 5937035.46);
    model.restoring_force(Eigen::Vector3d(0.0, 0.0, 0.002), r);  // 2 mm at floor 3
    EXPECT_NEAR(r[0], 0.002 * 5937035.46, 1e-7);
    EXPECT_NEAR(r[1], 0.002 * -14419970.78, 1e-7);
    EXPECT_NEAR(r[2], 0.002 * 9267275.51, 1e-7);
    // Superposition, and trial/commit leave a linear model path-independent.
    const Eigen::Vector3d d(0.003, -0.001, 0.004);
    Eigen::VectorXd r1(3), r2(3);
    model.restoring_force(d, r1);
    model.restoring_force(Eigen::Vector3d(0.5, 0.5, 0.5), r2);
    model.commit();
    model.restoring_force(d, r2);
    EXPECT_LT((r1 - r2).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((r1 - test::benchmark_case1_stiffness() * d).cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_EQ(&model.tangent_stiffness(), &model.initial_stiffness());
    // Undamped by default: C = 0.
    EXPECT_EQ(model.damping().to_dense().cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(LinearMdof, ExplicitDampingMatrix) {
  LinearMdofParameters cfg = benchmark_config(linalg::MatrixStorage::kDense);
  Eigen::MatrixXd C = 0.01 * test::benchmark_case1_stiffness();
  cfg.damping = DampingMatrix{linalg::StructuralMatrix(C)};
  LinearMdofModel model;
  model.configure(cfg);
  EXPECT_EQ(model.damping().dense(), C);
  EXPECT_FALSE(model.rayleigh().has_value());
  cfg.damping = DampingMatrix{linalg::StructuralMatrix(Eigen::MatrixXd(Eigen::MatrixXd::Identity(2, 2)))};
  EXPECT_CONTAINS(configure_error(cfg), "damping matrix C is 2x2 but the model has 3 DOFs");
}

TEST(LinearMdof, RejectsNonSymmetricMass) {
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    LinearMdofParameters cfg = benchmark_config(linalg::MatrixStorage::kDense);
    Eigen::MatrixXd M = test::benchmark_case1_mass();
    M(0, 1) = 5.0;
    cfg.mass_kg = linalg::StructuralMatrix(M).converted(storage);
    const std::string msg = configure_error(cfg);
    EXPECT_CONTAINS(msg, "mass matrix M is not symmetric");
    EXPECT_CONTAINS(msg, "[0,1] = 5");
  }
}

TEST(LinearMdof, RejectsNonPositiveDefiniteMass) {
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    LinearMdofParameters cfg = benchmark_config(linalg::MatrixStorage::kDense);
    Eigen::MatrixXd M = test::benchmark_case1_mass();
    M(0, 1) = M(1, 0) = 2000.0;  // positive diagonal, eigenvalue 1000 − 2000 < 0
    cfg.mass_kg = linalg::StructuralMatrix(M).converted(storage);
    EXPECT_CONTAINS(configure_error(cfg), "mass matrix M is not positive definite");
    M = test::benchmark_case1_mass();
    M(2, 2) = 0.0;  // a massless DOF
    cfg.mass_kg = linalg::StructuralMatrix(M).converted(storage);
    EXPECT_CONTAINS(configure_error(cfg), "diagonal entry [2,2] = 0");
    M(2, 2) = -1.0;
    cfg.mass_kg = linalg::StructuralMatrix(M).converted(storage);
    EXPECT_CONTAINS(configure_error(cfg), "[2,2] = -1");
  }
}

TEST(LinearMdof, RejectsMismatchedAndMalformedMatrices) {
  LinearMdofParameters cfg = benchmark_config(linalg::MatrixStorage::kDense);
  cfg.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd(Eigen::MatrixXd::Identity(2, 2)));
  EXPECT_CONTAINS(configure_error(cfg), "stiffness matrix K is 3x3 but mass matrix M is 2x2");

  cfg = benchmark_config(linalg::MatrixStorage::kDense);
  cfg.stiffness_n_per_m = linalg::StructuralMatrix(Eigen::MatrixXd(Eigen::MatrixXd::Identity(3, 4)));
  EXPECT_CONTAINS(configure_error(cfg), "stiffness matrix K is not square: 3 rows x 4 columns");

  cfg = benchmark_config(linalg::MatrixStorage::kDense);
  cfg.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd(0, 0));
  EXPECT_CONTAINS(configure_error(cfg), "mass matrix M is empty");

  cfg = benchmark_config(linalg::MatrixStorage::kDense);
  Eigen::MatrixXd K = test::benchmark_case1_stiffness();
  K(1, 1) = -1.0e6;
  cfg.stiffness_n_per_m = linalg::StructuralMatrix(K);
  EXPECT_CONTAINS(configure_error(cfg), "stiffness matrix K has a negative diagonal entry [1,1] = -1000000");

  K = test::benchmark_case1_stiffness();
  K(2, 0) += 1.0;  // asymmetry of 1 N/m on 3e7: well above round-off
  cfg.stiffness_n_per_m = linalg::StructuralMatrix(K);
  EXPECT_CONTAINS(configure_error(cfg), "stiffness matrix K is not symmetric");

  K = test::benchmark_case1_stiffness();
  K(0, 0) = std::numeric_limits<double>::quiet_NaN();
  cfg.stiffness_n_per_m = linalg::StructuralMatrix(K);
  EXPECT_CONTAINS(configure_error(cfg), "non-finite entry [0,0]");
}

TEST(LinearMdof, RejectsBadRayleighModes) {
  LinearMdofParameters cfg = benchmark_config(linalg::MatrixStorage::kDense);
  cfg.damping = RayleighFromModes{1, 4, 0.05, 0.05};
  EXPECT_CONTAINS(configure_error(cfg), "mode number 4 is out of range 1..3");
  cfg.damping = RayleighFromModes{0, 2, 0.05, 0.05};
  EXPECT_CONTAINS(configure_error(cfg), "mode number 0 is out of range");
  cfg.damping = RayleighFromModes{2, 2, 0.05, 0.05};
  EXPECT_CONTAINS(configure_error(cfg), "must differ");
}

TEST(LinearMdof, FailedConfigureKeepsThePreviousModel) {
  LinearMdofModel model;
  model.configure(benchmark_config(linalg::MatrixStorage::kDense));
  LinearMdofParameters bad = benchmark_config(linalg::MatrixStorage::kDense);
  bad.damping = RayleighFromModes{1, 7, 0.05, 0.05};
  EXPECT_THROW(model.configure(bad), std::invalid_argument);
  EXPECT_EQ(model.dofs(), 3);
  EXPECT_EQ(model.initial_stiffness().dense(), Eigen::MatrixXd(test::benchmark_case1_stiffness()));
}

}  // namespace
}  // namespace rpsd::substructure
