// one_actuator: OpenFresco's ESOneActuator (`DOF`), with the actuator's length so that its
// stroke, line and fixed end are the lab's.
#include "rpsd/setups/setup_kinds.h"
#include "setup_reading.h"

namespace rpsd::setups {

OneActuatorParameters OneActuatorParameters::read(config::Source& section, Geometry geometry) {
  OneActuatorParameters p;
  p.geometry = geometry;
  p.motion =
      section.choice("dof", {"translation_x", "translation_y"},
                     "the translation of the control point the actuator drives (OpenFresco's DOF)") == "translation_y"
          ? DofMotion::kTranslationY
          : DofMotion::kTranslationX;
  p.actuator_length_m = section.number(
      "actuator_length_m", reading::length("the actuator's length, fixed end to attachment, at the reference "
                                           "configuration (pin to pin)"));
  p.common = CommonSetupConfig::read(section, 1, true);
  reading::require_valid(section, "actuator_length_m", p.planar());
  return p;
}

PlanarGeometry OneActuatorParameters::planar() const {
  PlanarGeometry g;
  g.geometry = geometry;
  g.dof_count = 1;
  g.dofs[0] = motion;
  // Behind the control point along its DOF: a positive stroke is a positive displacement.
  g.actuators[0].name = "actuator";
  g.actuators[0].attachment_m = {0.0, 0.0};
  g.actuators[0].fixed_end_m = motion == DofMotion::kTranslationY ? Eigen::Vector2d(0.0, -actuator_length_m)
                                                                  : Eigen::Vector2d(-actuator_length_m, 0.0);
  common.apply(g);
  return g;
}

}  // namespace rpsd::setups
