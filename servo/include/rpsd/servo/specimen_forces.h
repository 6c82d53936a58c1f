// Forces of the specimen the actuator drives: elastic spring (linear or bilinear),
// viscous damping and regularised Coulomb friction. Inline: the plant evaluates them 32
// times per control step.
#pragma once

#include <cmath>

#include "rpsd/servo/servo_parameters.h"

namespace rpsd::servo {

/// Elastic spring force at displacement x; bilinear springs soften beyond the change
/// displacement symmetrically. Real-time safe.
inline double spring_force_n(const SpecimenStiffness& stiffness, double displacement_m) {
  const double magnitude = std::abs(displacement_m);
  if (!stiffness.is_bilinear() || magnitude <= stiffness.change_displacement_m) {
    return stiffness.initial_n_per_m * displacement_m;
  }
  const double force = stiffness.initial_n_per_m * stiffness.change_displacement_m +
                       stiffness.secondary_n_per_m * (magnitude - stiffness.change_displacement_m);
  return std::copysign(force, displacement_m);
}

/// tanh for the friction law, within 2 ulps of std::tanh at about half its cost here: exactly
/// +-1 where tanh rounds to +-1 in double precision (|x| > 19.07), 1 - 2 / (e^{2|x|} + 1) from
/// 0.55 on, and std::tanh below that, where the exponential form would cancel. Real-time safe.
inline double regularisation_tanh(double x) {
  const double a = std::abs(x);
  if (a > 19.1) return std::copysign(1.0, x);
  if (a < 0.55) return std::tanh(x);
  return std::copysign(1.0 - 2.0 / (std::exp(2.0 * a) + 1.0), x);
}

/// Coulomb friction F_c, regularised as F_c tanh(v / v_reg) so that a fixed-step integrator
/// can pass through zero velocity; takes 1 / v_reg, which the plant computes once.
/// Real-time safe.
inline double friction_force_n(double friction_force_n, double inverse_regularisation_velocity_s_per_m,
                               double velocity_m_per_s) {
  if (friction_force_n == 0.0) return 0.0;
  return friction_force_n * regularisation_tanh(velocity_m_per_s * inverse_regularisation_velocity_s_per_m);
}

}  // namespace rpsd::servo
