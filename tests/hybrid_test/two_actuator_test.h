// A two-DOF test (x, θ) for setups' tests: each DOF its own actuator on a specimen of 2k, or
// both driven by two actuators at heights +1 m and -1 m (J = [[1, -1], [1, 1]]) each on a
// specimen of k, which Jᵀ diag(k, k) J makes the same DOF-diagonal diag(2k, 2k).
#pragma once

#include <Eigen/Core>

#include "rpsd/hybrid_test/hybrid_test_config.h"

namespace rpsd::hybrid_test {

inline constexpr double kK = 4.0e5;  // N/m: each actuator's specimen in the setup

inline TestConfig two_dof_test(double plant_stiffness_n_per_m) {
  TestConfig t;
  t.name = "two-dof";
  substructure::LinearMdofParameters model;
  Eigen::MatrixXd m(2, 2);
  m << 3000.0, 0.0, 0.0, 1500.0;
  model.mass_kg = linalg::StructuralMatrix(m);
  model.stiffness_n_per_m = linalg::StructuralMatrix(Eigen::MatrixXd::Zero(2, 2));  // the specimen's
  Eigen::MatrixXd c(2, 2);
  c << 900.0, -100.0, -100.0, 600.0;
  model.damping = substructure::DampingMatrix{linalg::StructuralMatrix(c)};
  t.structure = model;
  for (int d = 0; d < 2; ++d) {
    ExperimentalChannel channel;
    channel.dof = {d, d, 1.0, 1.0, 2.0 * kK};
    channel.restoring_force = coordinator::RestoringForceSource::kMeasuredForce;
    t.experimental.push_back(channel);
  }
  t.influence = Eigen::VectorXd::Ones(2);
  t.plant = servo::PureDelayParameters{0.0, plant_stiffness_n_per_m, 8192.0, {}, {}};
  t.control_rate_hz = 1024.0;
  t.record_dofs = {0, 1};
  t.initial_displacement_m = Eigen::Vector2d(0.004, 0.003);
  t.duration_s = 1.0;
  return t;
}

inline setups::PlanarGeometry symmetric_pair(setups::Geometry geometry) {
  setups::PlanarGeometry g;
  g.geometry = geometry;
  g.dof_count = 2;
  g.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation, setups::DofMotion::kTranslationX};
  g.actuators[0] = {"top", {-1.5, 1.0}, {0.0, 1.0}};
  g.actuators[1] = {"bottom", {-1.5, -1.0}, {0.0, -1.0}};
  return g;
}

inline TestConfig with_setup(setups::Geometry geometry = setups::Geometry::kLinear) {
  TestConfig t = two_dof_test(kK);
  ExperimentalSetupSite site;
  site.channels = {0, 1};
  setups::PlanarActuatorsParameters planar;
  planar.geometry = symmetric_pair(geometry);
  site.setup = planar;
  t.setups = {site};
  return t;
}

}  // namespace rpsd::hybrid_test
