// Shear building: assembled stiffness against the hand-assembled tridiagonal matrix,
// 2-story frequencies against the closed form, nonlinear stories and trial/commit.

#include "rpsd/substructure/shear_building.h"
#include "rpsd/substructure/modal.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rpsd::substructure {
namespace {

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

ShearBuildingParameters linear_building(std::vector<double> m, std::vector<double> k) {
  ShearBuildingParameters c;
  c.floor_masses_kg = std::move(m);
  for (double ki : k) c.story_springs.emplace_back(LinearSpringParameters{ki});
  return c;
}

TEST(ShearBuilding, StiffnessMatchesHandAssembledTridiagonal) {
  // Stories k = 4, 3, 2, 1 MN/m (ground to roof), by hand:
  Eigen::Matrix4d K_hand;
  K_hand << 7, -3, 0, 0, -3, 5, -2, 0, 0, -2, 3, -1, 0, 0, -1, 1;
  K_hand *= 1e6;
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    ShearBuildingParameters c = linear_building({1e3, 2e3, 3e3, 4e3}, {4e6, 3e6, 2e6, 1e6});
    c.storage = storage;
    ShearBuilding b;
    b.configure(c);
    EXPECT_EQ(b.dofs(), 4);
    EXPECT_EQ(b.initial_stiffness().is_sparse(), storage == linalg::MatrixStorage::kSparse);
    EXPECT_EQ(b.initial_stiffness().to_dense(), Eigen::MatrixXd(K_hand));
    EXPECT_EQ(b.mass().to_dense(), Eigen::MatrixXd(Eigen::Vector4d(1e3, 2e3, 3e3, 4e3).asDiagonal()));
    // Linear springs: R(d) = K d and the tangent stays K.
    const Eigen::Vector4d d(0.001, 0.003, -0.002, 0.004);
    Eigen::VectorXd r(4);
    b.restoring_force(d, r);
    EXPECT_LT((r - K_hand * d).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_EQ(b.tangent_stiffness().to_dense(), Eigen::MatrixXd(K_hand));
    // Story shears: V1 = k1 d1 = 4 kN, V2 = k2 (d2 − d1) = 6 kN, ...
    EXPECT_NEAR(b.trial_story_forces()[0], 4e3, 1e-9);
    EXPECT_NEAR(b.trial_story_forces()[1], 6e3, 1e-9);
    EXPECT_NEAR(b.trial_story_forces()[2], -1e4, 1e-9);
    EXPECT_NEAR(b.trial_story_forces()[3], 6e3, 1e-9);
  }
}

TEST(ShearBuilding, TwoStoryFrequenciesMatchClosedForm) {
  // det(K − ω² M) = 0:  m1 m2 ω⁴ − (m1 k2 + m2 (k1 + k2)) ω² + k1 k2 = 0.
  const double m1 = 2.5e4, m2 = 1.8e4, k1 = 4.0e7, k2 = 2.2e7;
  ShearBuilding b;
  b.configure(linear_building({m1, m2}, {k1, k2}));
  const double B = m1 * k2 + m2 * (k1 + k2), D = std::sqrt(B * B - 4.0 * m1 * m2 * k1 * k2);
  const double w1 = std::sqrt((B - D) / (2.0 * m1 * m2)), w2 = std::sqrt((B + D) / (2.0 * m1 * m2));
  const Eigen::VectorXd w = natural_frequencies_rad_s(b.mass(), b.initial_stiffness());
  EXPECT_NEAR(w[0], w1, 1e-12 * w1);
  EXPECT_NEAR(w[1], w2, 1e-12 * w2);
}

TEST(ShearBuilding, RayleighDampingUsesInitialStiffness) {
  ShearBuildingParameters c = linear_building({1e3, 1e3, 1e3}, {3e6, 2e6, 1e6});
  c.story_springs[0] = BilinearSpringParameters{3e6, 3e4, 0.1};  // initial stiffness still 3e6
  c.damping = RayleighFromFrequencies{10.0, 30.0, 0.05, 0.05};   // a0 = 0.75, a1 = 0.0025
  ShearBuilding b;
  b.configure(c);
  const Eigen::MatrixXd expected = 0.75 * b.mass().to_dense() + 0.0025 * b.initial_stiffness().to_dense();
  EXPECT_LT((b.damping().to_dense() - expected).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ShearBuilding, BilinearFirstStoryYieldsAndTangentFollows) {
  const double k1 = 2e6, fy = 2e4, alpha = 0.1, k2 = 1e6;
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    ShearBuildingParameters c;
    c.floor_masses_kg = {1e3, 1e3};
    c.story_springs = {BilinearSpringParameters{k1, fy, alpha}, LinearSpringParameters{k2}};
    c.storage = storage;
    ShearBuilding b;
    b.configure(c);
    Eigen::VectorXd r(2);
    // Floor 1 at 30 mm, floor 2 at 40 mm: story 1 at B of the bilinear path (24 kN),
    // story 2 elastic at 10 mm drift (10 kN).
    b.restoring_force(Eigen::Vector2d(0.030, 0.040), r);
    EXPECT_NEAR(r[0], 2.4e4 - 1.0e4, 1e-6);
    EXPECT_NEAR(r[1], 1.0e4, 1e-6);
    EXPECT_NEAR(r.sum(), 2.4e4, 1e-6);  // the floor forces add up to the base shear
    const Eigen::MatrixXd Kt = b.tangent_stiffness().to_dense();
    EXPECT_DOUBLE_EQ(Kt(0, 0), alpha * k1 + k2);
    EXPECT_DOUBLE_EQ(Kt(0, 1), -k2);
    EXPECT_DOUBLE_EQ(Kt(1, 1), k2);
    EXPECT_EQ(b.initial_stiffness().coeff(0, 0), k1 + k2);  // K0 untouched
    // Not committed: a small trial is elastic from the virgin state.
    b.restoring_force(Eigen::Vector2d(0.005, 0.005), r);
    EXPECT_NEAR(r[0], k1 * 0.005, 1e-6);
    EXPECT_DOUBLE_EQ(b.tangent_stiffness().coeff(0, 0), k1 + k2);
    // Commit the yielded state, then unload: story 1 comes back along k0.
    b.restoring_force(Eigen::Vector2d(0.030, 0.040), r);
    b.commit();
    b.restoring_force(Eigen::Vector2d(0.020, 0.030), r);
    EXPECT_NEAR(r[0] + r[1], 2.4e4 - k1 * 0.010, 1e-6);
  }
}

TEST(ShearBuilding, TrialTwiceWithoutCommitGivesTheSameForces) {
  ShearBuildingParameters c;
  c.floor_masses_kg = {1e3, 1e3, 1e3};
  BoucWenSpringParameters bw;
  bw.stiffness_n_per_m = 1e6;
  bw.post_yield_ratio = 0.05;
  bw.beta = bw.gamma = 1.0 / (2.0 * 1e-4);  // n = 2, z_max = 10 mm
  bw.n = 2.0;
  c.story_springs = {bw, bw, bw};
  ShearBuilding b;
  b.configure(c);
  Eigen::VectorXd r1(3), r2(3), r3(3);
  const Eigen::Vector3d d(0.01, 0.025, 0.03);
  b.restoring_force(Eigen::Vector3d(0.004, 0.006, 0.009), r1);
  b.commit();
  b.restoring_force(d, r1);
  b.restoring_force(d, r2);
  EXPECT_EQ(r1, r2);
  b.restoring_force(Eigen::Vector3d(-0.05, 0.05, -0.05), r3);  // uncommitted excursion
  b.restoring_force(d, r2);
  EXPECT_EQ(r1, r2);
}

TEST(ShearBuilding, RejectsBadInput) {
  auto error = [](const ShearBuildingParameters& c) -> std::string {
    ShearBuilding b;
    try {
      b.configure(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_CONTAINS(error(linear_building({}, {})), "floor_masses_kg is empty");
  EXPECT_CONTAINS(error(linear_building({1e3, 1e3}, {1e6})), "2 floor masses but 1 story springs");
  EXPECT_CONTAINS(error(linear_building({1e3, -5.0}, {1e6, 1e6})), "floor 2: mass must be positive, got -5 kg");
  EXPECT_CONTAINS(error(linear_building({1e3, 1e3}, {1e6, -2e6})),
                  "story 2: linear spring: stiffness_n_per_m must be positive, got -2000000");
  ShearBuildingParameters c = linear_building({1e3, 1e3}, {1e6, 1e6});
  c.story_springs[0] = BilinearSpringParameters{1e6, -1.0, 0.1};
  EXPECT_CONTAINS(error(c), "story 1: bilinear spring: yield_force_n must be positive");
  c = linear_building({1e3, 1e3}, {1e6, 1e6});
  c.damping = RayleighFromModes{1, 3, 0.05, 0.05};
  EXPECT_CONTAINS(error(c), "mode number 3 is out of range 1..2");
}

}  // namespace
}  // namespace rpsd::substructure
