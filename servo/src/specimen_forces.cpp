#include "rpsd/servo/specimen_forces.h"

#include <cmath>

namespace rpsd::servo {

double spring_force_n(const SpecimenStiffness& stiffness, double displacement_m) {
  const double magnitude = std::abs(displacement_m);
  if (!stiffness.is_bilinear() || magnitude <= stiffness.change_displacement_m) {
    return stiffness.initial_n_per_m * displacement_m;
  }
  const double force = stiffness.initial_n_per_m * stiffness.change_displacement_m +
                       stiffness.secondary_n_per_m * (magnitude - stiffness.change_displacement_m);
  return std::copysign(force, displacement_m);
}

double friction_force_n(const SpecimenParameters& specimen, double velocity_m_per_s) {
  if (specimen.friction_force_n == 0.0) return 0.0;
  return specimen.friction_force_n *
         std::tanh(velocity_m_per_s / specimen.friction_regularisation_velocity_m_per_s);
}

}  // namespace rpsd::servo
