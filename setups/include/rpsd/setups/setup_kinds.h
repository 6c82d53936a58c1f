// Every experimental setup rpsd knows, registered in one place (the list below), like the
// compensators: each kind is its parameters (naming themselves with kName, reading their keys
// with read()) and the planar geometry they describe. A new kind is its own header and
// source plus one entry here.
//
// The lab's frame (docs/experimental-setups.md): x horizontal, y up, rotation counterclockwise,
// the control point at the origin at the reference configuration. Each kind places its
// actuators as the OpenFresco setup it is named after does.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>

#include "rpsd/config/kind_list.h"
#include "rpsd/config/source.h"
#include "rpsd/setups/planar_setup.h"

namespace rpsd::setups {

// Which side of the specimen an actuator's fixed end (its reaction frame) is on: OpenFresco's
// -posAct. Its positive stroke pushes the specimen away from that side.
enum class ActuatorSide : std::uint8_t { kLeft, kRight };

// What every kind may give besides its dimensions: the Newton solve's bounds and, for the
// kinds that name their actuators themselves, other names (`actuator_names`).
struct CommonSetupConfig {
  std::array<std::string, kMaxSetupDofs> actuator_names{};  // empty: the kind's own names
  double newton_tolerance_m = 1e-12;
  int max_newton_iterations = 25;
  // `names_key`: whether the section may rename its actuators (`actuator_names`).
  static CommonSetupConfig read(config::Source& section, int actuators, bool names_key);
  // Puts the bounds, and the names given, into `g`.
  void apply(PlanarGeometry& g) const;
};

// One actuator on one translation of the control point (OpenFresco's ESOneActuator): its fixed
// end at actuator_length_m behind the control point along the DOF, so a positive stroke is a
// positive displacement.
struct OneActuatorParameters {
  static constexpr std::string_view kName = "one_actuator";
  static constexpr std::string_view kSummary = "one actuator along one translation of the control point";
  static OneActuatorParameters read(config::Source& section, Geometry geometry);
  Geometry geometry = Geometry::kLinear;
  DofMotion motion = DofMotion::kTranslationX;
  double actuator_length_m = 0.0;
  CommonSetupConfig common;
  PlanarGeometry planar() const;
};

// Two parallel horizontal actuators driving translation and rotation (OpenFresco's
// ESTwoActuators2d, `La1 La2 L -posAct`: a column top or a beam end). Actuator 1 acts at the
// control point, actuator 2 at distance_between_actuators_m above it; both fixed ends on
// `side`.
struct TwoActuatorsParameters {
  static constexpr std::string_view kName = "two_actuators";
  static constexpr std::string_view kSummary =
      "two parallel actuators driving the translation and rotation of the control point";
  static TwoActuatorsParameters read(config::Source& section, Geometry geometry);
  Geometry geometry = Geometry::kLinear;
  ActuatorSide side = ActuatorSide::kLeft;
  double actuator_length_m[2] = {0.0, 0.0};   // La1, La2
  double distance_between_actuators_m = 0.0;  // L
  CommonSetupConfig common;
  PlanarGeometry planar() const;
};

// One horizontal and two vertical actuators driving x, y and θ (OpenFresco's
// ESThreeActuators2d, and ESThreeActuatorsJntOff2d with joint offsets). The vertical
// actuators push up from below; the horizontal one acts at the control point's height from
// horizontal_actuator_side.
struct ThreeActuatorsParameters {
  static constexpr std::string_view kName = "three_actuators";
  static constexpr std::string_view kSummary =
      "one horizontal and two vertical actuators driving x, y and rotation, with or without joint offsets";
  static ThreeActuatorsParameters read(config::Source& section, Geometry geometry);
  Geometry geometry = Geometry::kLinear;
  ActuatorSide horizontal_actuator_side = ActuatorSide::kLeft;  // -posAct1
  double actuator_length_m[3] = {0.0, 0.0, 0.0};                // La1 (horizontal), La2 (left), La3 (right)
  // ESThreeActuatorsJntOff2d's L1..L6 (ESThreeActuators2d's L1, L2 are [1], [2], the rest zero):
  // [0] the horizontal actuator's attachment beyond the left vertical actuator (left side only),
  // [1] the control point to the left vertical actuator, [2] to the right one, [3] the
  // horizontal actuator's attachment beyond the right vertical actuator (right side only),
  // [4] and [5] how far below the control point the left and right vertical actuators attach.
  double rigid_length_m[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  CommonSetupConfig common;
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

// "linear", "large_displacement": the `geometry` key's words.
std::string_view geometry_name(Geometry geometry) noexcept;

// The section's `kind` and `geometry` (linear | large_displacement, required) and that kind's
// keys; a geometry PlanarSetup refuses is an error at the kind's key that makes it so. Not
// real-time safe.
SetupConfig read_setup_config(config::Source& section);

// The geometry the configuration describes (checked when a PlanarSetup is made of it).
PlanarGeometry planar_geometry(const SetupConfig& config);

}  // namespace rpsd::setups
