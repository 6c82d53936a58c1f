// The damping of the whole structure (whole_structure_damping): the RTHS benchmark's reference
// building, its numerical part plus the specimen's stiffness and damping, has 5 % in every
// mode; and Rayleigh damping through modes 1 and 2 of the whole structure leaves mode 3 at the
// Rayleigh curve's value (10.1 %), where Rayleigh fitted to the numerical part alone gave
// 4.11 % and 4.85 % in the first two.
#include <gtest/gtest.h>

#include <cmath>

#include "../servo/paper_rig.h"
#include "../substructure/state_space_damping.h"
#include "file_text.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/substructure/modal.h"

namespace rpsd::hybrid_test {
namespace {

const std::filesystem::path kCase1 =
    rpsd::testing::source_dir() / "tests/hybrid_test/data/rths-case1-whole-structure-damping.yaml";

struct Whole {
  Eigen::MatrixXd m, c, k;
};

// M, the numerical part's C plus the specimens' own damping, and K0 with the specimens.
Whole whole_structure(const TestConfig& t) {
  const auto numerical = make_numerical_model(t);
  substructure::Partition partition;
  partition.configure(partition_config(t, numerical->dofs()));
  Whole w{numerical->mass().to_dense(), numerical->damping().to_dense(),
          partition.with_specimen_stiffness(numerical->initial_stiffness()).to_dense()};
  for (const auto& e : t.experimental) w.c(e.dof.dof, e.dof.dof) += e.specimen_damping_n_s_per_m;
  return w;
}

TEST(WholeStructureDamping, TheBenchmarksCase1HasFivePercentInEveryModeOfTheReferenceBuilding) {
  const auto d = scenarios::load_study(kCase1);
  const TestConfig& t = std::get<TestConfig>(d.study);
  ASSERT_DOUBLE_EQ(t.experimental[0].specimen_damping_n_s_per_m, 114.6);
  const Whole w = whole_structure(t);
  const std::vector<double> zeta = substructure::test::state_space_damping_ratios(w.m, w.c, w.k);
  ASSERT_EQ(zeta.size(), 3u);
  for (double z : zeta) EXPECT_NEAR(z, 0.05, 1e-9);
}

TEST(WholeStructureDamping, RayleighThroughTheWholeStructuresFirstTwoModesGivesTheRayleighCurveInTheThird) {
  std::string text = text_of(kCase1);
  const std::string modal = "modal: {damping_ratios: [0.05]}";
  text.replace(text.find(modal), modal.size(),
               "rayleigh: {mode_a: 1, mode_b: 2, damping_ratio_a: 0.05, damping_ratio_b: 0.05}");
  const auto d = scenarios::parse_study(text, kCase1);
  const Whole w = whole_structure(std::get<TestConfig>(d.study));
  const std::vector<double> zeta = substructure::test::state_space_damping_ratios(w.m, w.c, w.k);
  // The Rayleigh curve zeta(w) = a0 / (2 w) + a1 w / 2 through 5 % at w1 and w2 of the whole
  // structure: a1 = 2 zeta / (w1 + w2), a0 = a1 w1 w2.
  const Eigen::VectorXd omega =
      substructure::natural_frequencies_rad_s(linalg::StructuralMatrix(w.m), linalg::StructuralMatrix(w.k));
  const double a1 = 2.0 * 0.05 / (omega[0] + omega[1]), a0 = a1 * omega[0] * omega[1];
  ASSERT_EQ(zeta.size(), 3u);
  EXPECT_NEAR(zeta[0], 0.05, 2e-3);  // the specimen's own damping (114.6 N s/m) comes on top
  EXPECT_NEAR(zeta[1], 0.05, 2e-3);
  EXPECT_NEAR(zeta[2], a0 / (2.0 * omega[2]) + a1 * omega[2] / 2.0, 2e-3);
  EXPECT_NEAR(zeta[2], 0.101, 1e-3);
}

TEST(WholeStructureDamping, StructureDampingAndWholeStructureDampingTogetherAreRefused) {
  std::string text = text_of(kCase1);
  const std::string anchor = "experimental:";
  text.replace(
      text.find(anchor), anchor.size(),
      "  damping:\n    rayleigh: {mode_a: 1, mode_b: 2, damping_ratio_a: 0.05, damping_ratio_b: 0.05}\n" + anchor);
  EXPECT_THROW((void)scenarios::parse_study(text, kCase1), std::exception);
}

}  // namespace
}  // namespace rpsd::hybrid_test

namespace rpsd::hybrid_test {
namespace {

// Case 1 with the specimen's mass too (the benchmark's m_e = 29.13 kg).
TestConfig case1_with_specimen_mass(double mass_kg) {
  std::string text = text_of(kCase1);
  const std::string damping = "specimen_damping_n_s_per_m: 114.6\n";
  text.insert(text.find(damping) + damping.size(), "    specimen_mass_kg: " + std::to_string(mass_kg) + "\n");
  return std::get<TestConfig>(scenarios::parse_study(text, kCase1).study);
}

TEST(WholeStructureDamping, TheSpecimensMassIsLeftToItsForceAndTheReferenceKeepsTheWholeBuilding) {
  const TestConfig t = case1_with_specimen_mass(29.13);
  const auto test_part = make_numerical_model(t);
  EXPECT_NEAR(test_part->mass().to_dense()(0, 0), 1000.0 - 29.13, 1e-9);
  EXPECT_EQ(test_part->mass().to_dense()(1, 1), 1000.0);
  // The ground motion loads the whole building, specimen included.
  EXPECT_EQ(whole_structure_mass(t).to_dense()(0, 0), 1000.0);
  // The reference (perfect actuator, specimen k x only) keeps the specimen's mass and damping.
  const auto reference = make_numerical_model(t, SpecimenShare::kKeptInNumericalPart);
  EXPECT_EQ(reference->mass().to_dense()(0, 0), 1000.0);
  EXPECT_NEAR(reference->damping().to_dense()(0, 0), test_part->damping().to_dense()(0, 0) + 114.6, 1e-9);
  // The test's numerical part with the specimen's m, c and k is the reference building: 5 %
  // in every mode of M, C, K0 (state-matrix eigenvalues).
  Eigen::MatrixXd m = test_part->mass().to_dense(), c = test_part->damping().to_dense();
  m(0, 0) += 29.13;
  c(0, 0) += 114.6;
  substructure::Partition partition;
  partition.configure(partition_config(t, test_part->dofs()));
  const Eigen::MatrixXd k = partition.with_specimen_stiffness(test_part->initial_stiffness()).to_dense();
  for (double z : substructure::test::state_space_damping_ratios(m, c, k)) EXPECT_NEAR(z, 0.05, 1e-9);
}

TEST(WholeStructureDamping, ASpecimenHeavierThanItsFloorIsRefusedNamingTheKey) {
  try {
    (void)case1_with_specimen_mass(1500.0);
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("specimen_mass_kg"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("experimental"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::hybrid_test
