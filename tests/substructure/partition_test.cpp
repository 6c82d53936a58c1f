// Numerical/experimental partition: DOF ↔ channel mapping, scale factors, ground-motion load.

#include "rpsd/substructure/partition.h"
#include "rpsd/substructure/ground_motion_load.h"
#include "rpsd/substructure/shear_building.h"

#include <gtest/gtest.h>

namespace rpsd::substructure {
namespace {

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

// 5 DOFs; DOF 3 on channel 1 at half scale, DOF 1 on channel 0 at quarter scale. Equal-stress
// similitude at length scale λ gives force_scale = 1/λ².
PartitionConfig two_specimens() {
  PartitionConfig c;
  c.dofs = 5;
  c.experimental = {{3, 1, 0.5, 4.0, 2.0e5}, {1, 0, 0.25, 16.0, 1.0e5}};
  c.influence = Eigen::VectorXd::Ones(5);
  return c;
}

TEST(Partition, MapsDofsToChannelsWithScales) {
  Partition p;
  p.configure(two_specimens());
  EXPECT_EQ(p.dofs(), 5);
  EXPECT_EQ(p.channels(), 2);
  EXPECT_EQ(p.channel_of(1), 0);
  EXPECT_EQ(p.channel_of(3), 1);
  EXPECT_EQ(p.channel_of(0), -1);
  EXPECT_EQ(p.channel_of(7), -1);
  EXPECT_TRUE(p.is_experimental(3));
  EXPECT_FALSE(p.is_experimental(2));
  EXPECT_EQ(p.numerical_dofs(), (std::vector<Eigen::Index>{0, 2, 4}));

  const Eigen::VectorXd d = (Eigen::VectorXd(5) << 0.01, 0.02, 0.03, 0.04, 0.05).finished();
  Eigen::VectorXd u(2);
  p.extract_commands(d, u);
  EXPECT_DOUBLE_EQ(u[0], 0.25 * 0.02);  // channel 0 ← DOF 1, quarter scale
  EXPECT_DOUBLE_EQ(u[1], 0.5 * 0.04);   // channel 1 ← DOF 3, half scale

  // Measured displacements map back to model scale; numerical DOFs untouched.
  Eigen::VectorXd dm = Eigen::VectorXd::Constant(5, -1.0);
  p.measured_to_model_displacements(Eigen::Vector2d(0.005, 0.02), dm);
  EXPECT_EQ(dm, (Eigen::VectorXd(5) << -1.0, 0.02, -1.0, 0.04, -1.0).finished());

  const Eigen::Vector2d f(100.0, 300.0);  // N measured on channels 0 and 1
  Eigen::VectorXd r_exp = Eigen::VectorXd::Constant(5, 9.0);
  p.scatter_forces(f, r_exp);
  EXPECT_EQ(r_exp, (Eigen::VectorXd(5) << 0.0, 1600.0, 0.0, 1200.0, 0.0).finished());
  Eigen::VectorXd r = Eigen::VectorXd::Constant(5, 1.0);
  p.add_forces(f, r);
  EXPECT_EQ(r, (Eigen::VectorXd(5) << 1.0, 1601.0, 1.0, 1201.0, 1.0).finished());
}

TEST(Partition, SpecimenStiffnessSeenFromTheModel) {
  // An elastic specimen (f = k x) driven through the partition acts on the model as
  // force_scale · displacement_scale · k: the same as with_specimen_stiffness() adds to K.
  Partition p;
  p.configure(two_specimens());
  const Eigen::VectorXd d = (Eigen::VectorXd(5) << 0.0, 0.02, 0.0, -0.01, 0.0).finished();
  Eigen::VectorXd u(2), f(2), r(5);
  p.extract_commands(d, u);
  f << 1.0e5 * u[0], 2.0e5 * u[1];  // specimen forces, specimen units
  p.scatter_forces(f, r);
  const linalg::StructuralMatrix K =
      p.with_specimen_stiffness(linalg::StructuralMatrix(Eigen::MatrixXd(Eigen::MatrixXd::Zero(5, 5))));
  EXPECT_LT((r - K.dense() * d).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_DOUBLE_EQ(K.coeff(1, 1), 16.0 * 0.25 * 1.0e5);
  EXPECT_DOUBLE_EQ(K.coeff(3, 3), 4.0 * 0.5 * 2.0e5);
  // Sparse storage is kept.
  const linalg::StructuralMatrix Ks = p.with_specimen_stiffness(linalg::StructuralMatrix(linalg::SparseMatrix(5, 5)));
  EXPECT_TRUE(Ks.is_sparse());
  EXPECT_EQ(Ks.to_dense(), K.dense());
}

TEST(Partition, RejectsBadConfigurations) {
  auto error = [](const PartitionConfig& c) -> std::string {
    Partition p;
    try {
      p.configure(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  PartitionConfig c = two_specimens();
  c.experimental[1].dof = 5;
  EXPECT_CONTAINS(error(c), "experimental entry 1: DOF index 5 is out of range 0..4");
  c = two_specimens();
  c.experimental[1].dof = -1;
  EXPECT_CONTAINS(error(c), "DOF index -1 is out of range");
  c = two_specimens();
  c.experimental[1].dof = 3;
  EXPECT_CONTAINS(error(c), "experimental entry 1: DOF 3 is already experimental (entry 0)");
  c = two_specimens();
  c.experimental[1].actuator_channel = 1;
  EXPECT_CONTAINS(error(c), "actuator channel 1 is already used by entry 0");
  c = two_specimens();
  c.experimental[0].actuator_channel = 2;
  EXPECT_CONTAINS(error(c), "actuator channel 2 is out of range 0..1");
  c = two_specimens();
  c.experimental[0].displacement_scale = 0.0;
  EXPECT_CONTAINS(error(c), "displacement_scale must be positive");
  c = two_specimens();
  c.experimental[0].force_scale = -2.0;
  EXPECT_CONTAINS(error(c), "force_scale must be positive, got -2");
  c = two_specimens();
  c.experimental[0].specimen_stiffness_estimate_n_per_m = -1.0;
  EXPECT_CONTAINS(error(c), "specimen_stiffness_estimate_n_per_m must be non-negative");
  c = two_specimens();
  c.influence = Eigen::VectorXd::Ones(4);
  EXPECT_CONTAINS(error(c), "influence vector has 4 entries but the model has 5 DOFs");
  c = two_specimens();
  c.dofs = 0;
  EXPECT_CONTAINS(error(c), "dofs must be positive");
}

TEST(GroundMotionLoad, ShearBuildingIsMinusMassTimesAcceleration) {
  ShearBuildingParameters c;
  c.floor_masses_kg = {1.0e3, 2.0e3, 3.0e3};
  c.story_springs = {LinearSpringParameters{1e6}, LinearSpringParameters{1e6}, LinearSpringParameters{1e6}};
  ShearBuilding b;
  b.configure(c);
  GroundMotionLoad g;
  g.configure(b.mass(), Eigen::VectorXd::Ones(3));
  Eigen::VectorXd F(3);
  g.force(2.0, F);  // a_g = 2 m/s²: F_i = −m_i a_g
  EXPECT_EQ(F, Eigen::Vector3d(-2.0e3, -4.0e3, -6.0e3));
  // A coupled mass matrix and an influence vector selecting DOFs 0 and 2 (say, the
  // horizontal DOFs of a frame): F = −M ι a_g.
  Eigen::Matrix3d M;
  M << 4, 1, 0, 1, 4, 1, 0, 1, 4;
  g.configure(linalg::StructuralMatrix(Eigen::MatrixXd(M)).converted(linalg::MatrixStorage::kSparse),
              Eigen::Vector3d(1, 0, 1));
  g.force(-0.5, F);
  EXPECT_EQ(F, Eigen::Vector3d(2.0, 1.0, 2.0));
  EXPECT_THROW(g.configure(b.mass(), Eigen::VectorXd::Ones(2)), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::substructure
