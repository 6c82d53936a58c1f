// two_actuators: OpenFresco's ESTwoActuators2d (`La1 La2 L -posAct`). Actuator 1 acts at the
// control point, actuator 2 on the rigid link at L above it, both horizontal with their fixed
// ends on one side; the DOFs are the control point's x and rotation.
#include "rpsd/setups/setup_kinds.h"
#include "setup_reading.h"

namespace rpsd::setups {

TwoActuatorsParameters TwoActuatorsParameters::read(config::Source& section, Geometry geometry) {
  TwoActuatorsParameters p;
  p.geometry = geometry;
  p.side = reading::read_side(section, "actuators_side",
                              "where both actuators' fixed ends are (OpenFresco's -posAct): a positive stroke pushes "
                              "away from that side");
  const std::vector<double> lengths = section.numbers(
      "actuator_lengths_m",
      reading::length("La1, La2: each actuator's length, fixed end to attachment, at the reference configuration"), 2);
  p.distance_between_actuators_m = section.number(
      "distance_between_actuators_m",
      reading::length("L: from actuator 1's attachment (the control point) up to actuator 2's, along the specimen"));
  p.common = CommonSetupConfig::read(section, 2, true);
  reading::require_count(section, "actuator_lengths_m", lengths, 2);
  p.actuator_length_m[0] = lengths[0];
  p.actuator_length_m[1] = lengths[1];
  reading::require_valid(section, "distance_between_actuators_m", p.planar());
  return p;
}

PlanarGeometry TwoActuatorsParameters::planar() const {
  const double away = side == ActuatorSide::kRight ? 1.0 : -1.0;  // the fixed ends' side along x
  const double l = distance_between_actuators_m;
  PlanarGeometry g;
  g.geometry = geometry;
  g.dof_count = 2;
  g.dofs = {DofMotion::kTranslationX, DofMotion::kRotation, DofMotion::kTranslationX};
  g.actuators[0] = {"actuator_1", {away * actuator_length_m[0], 0.0}, {0.0, 0.0}};
  g.actuators[1] = {"actuator_2", {away * actuator_length_m[1], l}, {0.0, l}};
  common.apply(g);
  return g;
}

}  // namespace rpsd::setups
