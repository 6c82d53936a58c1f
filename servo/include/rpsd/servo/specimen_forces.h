// Forces of the specimen the actuator drives: elastic spring (linear or bilinear),
// viscous damping and regularised Coulomb friction.
#pragma once

#include "rpsd/servo/servo_parameters.h"

namespace rpsd::servo {

/// Elastic spring force at displacement x; bilinear springs soften beyond the change
/// displacement symmetrically. Real-time safe.
double spring_force_n(const SpecimenStiffness& stiffness, double displacement_m);

/// Coulomb friction, regularised as F_c tanh(v / v_reg) so that a fixed-step integrator can
/// pass through zero velocity. Real-time safe.
double friction_force_n(const SpecimenParameters& specimen, double velocity_m_per_s);

}  // namespace rpsd::servo
