// Forces of the specimen the actuator drives: elastic spring (linear or bilinear),
// viscous damping and regularised Coulomb friction. Inline: the plant evaluates them 32
// times per control step.
#pragma once

#include <cmath>

#include "rpsd/servo/regularised_tanh.h"
#include "rpsd/servo/servo_parameters.h"

namespace rpsd::servo {

// Elastic spring force at displacement x; bilinear springs soften beyond the change
// displacement symmetrically. Real-time safe.
inline double spring_force_n(const SpecimenStiffness& stiffness, double displacement_m) {
  const double magnitude = std::abs(displacement_m);
  if (!stiffness.is_bilinear() || magnitude <= stiffness.change_displacement_m) {
    return stiffness.initial_n_per_m * displacement_m;
  }
  const double force = stiffness.initial_n_per_m * stiffness.change_displacement_m +
                       stiffness.secondary_n_per_m * (magnitude - stiffness.change_displacement_m);
  return std::copysign(force, displacement_m);
}

// Coulomb friction F_c, regularised as F_c tanh(v / v_reg) so that a fixed-step integrator
// can pass through zero velocity; takes 1 / v_reg, which the plant computes once.
// Real-time safe.
inline double friction_force_n(double friction_force_n, double inverse_regularisation_velocity_s_per_m,
                               double velocity_m_per_s) {
  if (friction_force_n == 0.0) return 0.0;
  return friction_force_n * regularised_tanh(velocity_m_per_s * inverse_regularisation_velocity_s_per_m);
}

}  // namespace rpsd::servo
