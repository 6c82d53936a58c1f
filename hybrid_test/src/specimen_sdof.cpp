#include "rpsd/hybrid_test/specimen_sdof.h"

#include <cmath>
#include <utility>

namespace rpsd::hybrid_test {

TestConfig specimen_sdof_test(const SpecimenSdof& sdof) {
  const double m = sdof.mass_kg, k = sdof.stiffness_n_per_m;
  TestConfig t;
  t.name = "specimen-sdof";
  substructure::LinearMdofParameters model;
  model.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, m));
  model.stiffness_n_per_m = linalg::StructuralMatrix(Eigen::MatrixXd::Zero(1, 1));  // the spring is the specimen
  model.damping = substructure::DampingMatrix{
      linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, 2.0 * sdof.damping_ratio * std::sqrt(k * m)))};
  t.structure = model;
  ExperimentalChannel channel;
  channel.dof = {0, 0, 1.0, 1.0, k};
  channel.restoring_force = sdof.restoring_force;
  t.experimental = {channel};
  t.influence = Eigen::VectorXd::Ones(1);
  t.plant = sdof.plant;
  t.integrator = sdof.integrator;
  t.compensation = sdof.compensation;
  t.control_rate_hz = sdof.control_rate_hz;
  t.record_dofs = {0};
  if (sdof.ground_acceleration_m_per_s2.empty()) {
    t.initial_displacement_m = Eigen::VectorXd::Constant(1, sdof.initial_displacement_m);
    t.duration_s = sdof.duration_s;
  } else {
    const double dt_s = 1.0 / sdof.control_rate_hz;
    GroundMotion record;
    record.name = "record";
    record.dt_s = record.record_step_s = dt_s;
    record.acceleration_m_per_s2 = sdof.ground_acceleration_m_per_s2;
    t.ground_motion = std::move(record);
    t.initial_displacement_m = Eigen::VectorXd::Zero(1);
    t.duration_s = dt_s * static_cast<double>(sdof.ground_acceleration_m_per_s2.size() - 1);
  }
  return t;
}

}  // namespace rpsd::hybrid_test
