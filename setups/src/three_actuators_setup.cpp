// three_actuators: OpenFresco's ESThreeActuators2d (`La1 La2 La3 L1 L2 -posAct1`) and, with
// joint_offsets, ESThreeActuatorsJntOff2d (`La1 La2 La3 L1 L2 L3 L4 L5 L6`). The two vertical
// actuators push up from below at the left and right of the control point; the horizontal one
// acts at the control point's height. The DOFs are x, y and rotation.
#include "rpsd/setups/setup_kinds.h"
#include "setup_reading.h"

namespace rpsd::setups {

ThreeActuatorsParameters ThreeActuatorsParameters::read(config::Source& section, Geometry geometry) {
  ThreeActuatorsParameters p;
  p.geometry = geometry;
  p.horizontal_actuator_side = reading::read_side(
      section, "horizontal_actuator_side",
      "where the horizontal actuator's fixed end is (OpenFresco's -posAct1): a positive stroke pushes away from it");
  const std::vector<double> lengths =
      section.numbers("actuator_lengths_m",
                      reading::length("La1 (horizontal), La2 (left vertical), La3 (right vertical): each actuator's "
                                      "length, fixed end to attachment, at the reference configuration"),
                      3);
  p.rigid_length_m[1] = section.number(
      "left_actuator_distance_m",
      reading::distance("from the control point left to the left vertical actuator's line (L1; JntOff2d's L2)"));
  p.rigid_length_m[2] = section.number(
      "right_actuator_distance_m",
      reading::distance("from the control point right to the right vertical actuator's line (L2; JntOff2d's L3)"));
  if (auto offsets = section.optional_section(
          "joint_offsets", "ESThreeActuatorsJntOff2d: the actuators' pins away from the rigid link's line")) {
    const double horizontal = offsets->number(
        "horizontal_actuator_offset_m",
        reading::distance("the horizontal actuator's attachment beyond the vertical actuator on its side, outward "
                          "(JntOff2d's L1 on the left, L4 on the right)"));
    (p.horizontal_actuator_side == ActuatorSide::kLeft ? p.rigid_length_m[0] : p.rigid_length_m[3]) = horizontal;
    p.rigid_length_m[4] = offsets->number(
        "left_actuator_offset_m",
        reading::coordinate("how far below the control point the left vertical actuator attaches (JntOff2d's L5)"));
    p.rigid_length_m[5] = offsets->number(
        "right_actuator_offset_m",
        reading::coordinate("how far below the control point the right vertical actuator attaches (JntOff2d's L6)"));
    offsets->finish();
  }
  p.common = CommonSetupConfig::read(section, 3, true);
  reading::require_count(section, "actuator_lengths_m", lengths, 3);
  for (std::size_t i = 0; i < 3; ++i) p.actuator_length_m[i] = lengths[i];
  reading::require_valid(section, "left_actuator_distance_m", p.planar());
  return p;
}

PlanarGeometry ThreeActuatorsParameters::planar() const {
  const double left = rigid_length_m[1], right = rigid_length_m[2];
  const double left_below = rigid_length_m[4], right_below = rigid_length_m[5];
  PlanarGeometry g;
  g.geometry = geometry;
  g.dof_count = 3;
  g.dofs = {DofMotion::kTranslationX, DofMotion::kTranslationY, DofMotion::kRotation};
  if (horizontal_actuator_side == ActuatorSide::kLeft) {
    const double x = -(left + rigid_length_m[0]);
    g.actuators[0] = {"horizontal", {x - actuator_length_m[0], 0.0}, {x, 0.0}};
  } else {
    const double x = right + rigid_length_m[3];
    g.actuators[0] = {"horizontal", {x + actuator_length_m[0], 0.0}, {x, 0.0}};
  }
  g.actuators[1] = {"left", {-left, -left_below - actuator_length_m[1]}, {-left, -left_below}};
  g.actuators[2] = {"right", {right, -right_below - actuator_length_m[2]}, {right, -right_below}};
  common.apply(g);
  return g;
}

}  // namespace rpsd::setups
