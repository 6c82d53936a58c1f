// A lab's dimensions for each kind, shared by the setups' tests: lengths of the order of a
// strong-floor rig (actuators of 1.1 to 1.5 m, lever arms of 0.6 to 0.9 m), all different so
// that a swapped dimension shows.
#pragma once

#include "rpsd/setups/setup_kinds.h"

namespace rpsd::setups::examples {

inline OneActuatorParameters one_actuator(Geometry geometry, DofMotion motion = DofMotion::kTranslationX) {
  OneActuatorParameters p;
  p.geometry = geometry;
  p.motion = motion;
  p.actuator_length_m = 1.25;
  return p;
}

// La1 = 1.2, La2 = 1.5, L = 0.8.
inline TwoActuatorsParameters two_actuators(Geometry geometry, ActuatorSide side = ActuatorSide::kLeft) {
  TwoActuatorsParameters p;
  p.geometry = geometry;
  p.side = side;
  p.actuator_length_m[0] = 1.2;
  p.actuator_length_m[1] = 1.5;
  p.distance_between_actuators_m = 0.8;
  return p;
}

// La = 1.1, 1.3, 1.4; OpenFresco's JntOff2d L1..L6 = 0.2, 0.6, 0.9, 0.3, 0.15, 0.25 (only the
// one of L1, L4 on the horizontal actuator's side acts); without offsets L1 = L4 = L5 = L6 = 0.
inline ThreeActuatorsParameters three_actuators(Geometry geometry, ActuatorSide side = ActuatorSide::kLeft,
                                                bool joint_offsets = true) {
  ThreeActuatorsParameters p;
  p.geometry = geometry;
  p.horizontal_actuator_side = side;
  p.actuator_length_m[0] = 1.1;
  p.actuator_length_m[1] = 1.3;
  p.actuator_length_m[2] = 1.4;
  p.rigid_length_m[1] = 0.6;
  p.rigid_length_m[2] = 0.9;
  if (joint_offsets) {
    p.rigid_length_m[0] = 0.2;
    p.rigid_length_m[3] = 0.3;
    p.rigid_length_m[4] = 0.15;
    p.rigid_length_m[5] = 0.25;
  }
  return p;
}

// A general one: two inclined actuators and a horizontal one, as a rig with braces might have.
inline PlanarActuatorsParameters planar(Geometry geometry) {
  PlanarActuatorsParameters p;
  p.geometry.geometry = geometry;
  p.geometry.dof_count = 3;
  p.geometry.dofs = {DofMotion::kTranslationX, DofMotion::kRotation, DofMotion::kTranslationY};
  p.geometry.actuators[0] = {"west", {-1.3, 0.1}, {-0.2, 0.0}};
  p.geometry.actuators[1] = {"south_east", {1.0, -1.2}, {0.4, -0.1}};
  p.geometry.actuators[2] = {"south_west", {-0.9, -1.1}, {-0.5, -0.2}};
  return p;
}

}  // namespace rpsd::setups::examples
