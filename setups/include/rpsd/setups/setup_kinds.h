// Every experimental setup rpsd knows, registered in one place (the list below), like the
// compensators: each kind is its parameters (naming themselves with kName, reading their keys
// with read()) and the planar geometry they describe. A new kind is its own header and
// source plus one entry here.
#pragma once

#include <string_view>
#include <variant>

#include "rpsd/config/kind_list.h"
#include "rpsd/config/source.h"
#include "rpsd/setups/planar_setup.h"

namespace rpsd::setups {

// One actuator on one DOF (OpenFresco's ESOneActuator).
struct OneActuatorParameters {
  static constexpr std::string_view kName = "one_actuator";
  static constexpr std::string_view kSummary = "one actuator along one translation of the control point";
  static OneActuatorParameters read(config::Source& section, Geometry geometry);
  Geometry geometry = Geometry::kLinear;
  DofMotion motion = DofMotion::kTranslationX;
  double actuator_length_m = 0.0;
  PlanarGeometry planar() const;
};

// Two parallel actuators driving translation and rotation (OpenFresco's ESTwoActuators2d:
// a column top or a beam end).
struct TwoActuatorsParameters {
  static constexpr std::string_view kName = "two_actuators";
  static constexpr std::string_view kSummary =
      "two parallel actuators driving the translation and rotation of the control point";
  static TwoActuatorsParameters read(config::Source& section, Geometry geometry);
  Geometry geometry = Geometry::kLinear;
  double actuator_length_m[2] = {0.0, 0.0};
  double distance_between_actuators_m = 0.0;  // along the specimen, between the attachments
  double control_point_offset_m = 0.0;        // from the first actuator's attachment (kind's docs)
  PlanarGeometry planar() const;
};

// One horizontal and two vertical actuators driving x, y and θ (OpenFresco's
// ESThreeActuators2d, and ESThreeActuatorsJntOff2d with joint offsets).
struct ThreeActuatorsParameters {
  static constexpr std::string_view kName = "three_actuators";
  static constexpr std::string_view kSummary =
      "one horizontal and two vertical actuators driving x, y and rotation, with or without joint offsets";
  static ThreeActuatorsParameters read(config::Source& section, Geometry geometry);
  Geometry geometry = Geometry::kLinear;
  double actuator_length_m[3] = {0.0, 0.0, 0.0};
  // The kind's rigid lengths (OpenFresco's L0..L5 where they exist; zero offsets: no joint
  // offset). The implementation documents each with a figure in docs/experimental-setups.md.
  double rigid_length_m[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  PlanarGeometry planar() const;
};

// Any planar setup, from the actuators' fixed ends and attachment points.
struct PlanarActuatorsParameters {
  static constexpr std::string_view kName = "planar";
  static constexpr std::string_view kSummary =
      "actuators given by their fixed ends and attachment points in the plane, driving any of x, y and rotation";
  static PlanarActuatorsParameters read(config::Source& section, Geometry geometry);
  PlanarGeometry geometry;
  PlanarGeometry planar() const { return geometry; }
};

using SetupKinds = config::KindList<OneActuatorParameters, TwoActuatorsParameters, ThreeActuatorsParameters,
                                    PlanarActuatorsParameters>;
using SetupConfig = SetupKinds::Variant;

// The section's `kind` and `geometry` (linear | large_displacement) and that kind's keys.
// Not real-time safe.
SetupConfig read_setup_config(config::Source& section);

// The geometry the configuration describes (checked when a PlanarSetup is made of it).
PlanarGeometry planar_geometry(const SetupConfig& config);

}  // namespace rpsd::setups
