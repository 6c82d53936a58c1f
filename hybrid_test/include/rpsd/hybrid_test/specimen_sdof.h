// An elastic SDOF whose whole stiffness is the specimen's: the seed paper's Figure 8
// experiment, and the simplest whole test. The mass and the viscous damping are numerical;
// the spring is the specimen on one actuator channel. Not real-time safe.
#pragma once

#include <vector>

#include "rpsd/hybrid_test/hybrid_test_config.h"

namespace rpsd::hybrid_test {

struct SpecimenSdof {
  double mass_kg = 7080.0;
  double damping_ratio = 0.011;
  double stiffness_n_per_m = 700.8e3;
  double initial_displacement_m = 0.01;  // free vibration from here
  double control_rate_hz = 1024.0;
  double duration_s = 10.0;
  integrators::IntegratorConfig integrator = integrators::CentralDifferenceParameters{};
  compensation::CompensatorConfig compensation = compensation::PassThroughParameters{};
  servo::PlantConfig plant = servo::PureDelayParameters{0.0, 700.8e3, 8192.0, {}, {}};
  coordinator::RestoringForceSource restoring_force =
      coordinator::RestoringForceSource::kStiffnessTimesMeasuredDisplacement;
  // Ground acceleration at t = n / control_rate_hz (F = -m a_g); empty: free vibration.
  // With a record the test lasts as long as the record.
  std::vector<double> ground_acceleration_m_per_s2;
};

TestConfig specimen_sdof_test(const SpecimenSdof& sdof);

}  // namespace rpsd::hybrid_test
