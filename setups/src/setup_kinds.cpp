#include "rpsd/setups/setup_kinds.h"

#include <stdexcept>
#include <string>
#include <type_traits>

#include "setup_reading.h"

namespace rpsd::setups {

namespace reading {

ActuatorSide read_side(config::Source& section, std::string_view key, std::string_view meaning) {
  return section.choice(key, {"left", "right"}, meaning) == "right" ? ActuatorSide::kRight : ActuatorSide::kLeft;
}

void require_count(config::Source& section, std::string_view key, const std::vector<double>& values,
                   std::size_t count) {
  if (values.size() != count) {
    section.fail(key, "expected " + std::to_string(count) + " numbers, got " + std::to_string(values.size()));
  }
}

void require_valid(config::Source& section, std::string_view key, const PlanarGeometry& g) {
  try {
    const PlanarSetup probe(g);
  } catch (const std::invalid_argument& e) {
    section.fail(key, e.what());
  }
}

bool is_plain_name(std::string_view name) noexcept {
  if (name.empty()) return false;
  for (const char c : name) {
    const bool plain =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!plain) return false;
  }
  return true;
}

}  // namespace reading

CommonSetupConfig CommonSetupConfig::read(config::Source& section, int actuators, bool names_key) {
  CommonSetupConfig c;
  std::optional<std::vector<std::string>> names;
  if (names_key) {
    names = section.optional_texts("actuator_names",
                                   "the actuators' names in records and messages, in the kind's order", kMaxSetupDofs);
  }
  c.newton_tolerance_m = section.number_or(
      "newton_tolerance_m", c.newton_tolerance_m,
      config::Number{"m", "large displacement: the measured strokes are solved when every residual is below this", 0.0,
                     1e-3, true});
  c.max_newton_iterations = static_cast<int>(section.whole_number_or(
      "max_newton_iterations", 1, 100, c.max_newton_iterations,
      "large displacement: the Newton solve of the measured strokes fails (the test stops) after this many"));
  if (names) {
    if (names->size() != static_cast<std::size_t>(actuators)) {
      section.fail("actuator_names", "expected " + std::to_string(actuators) + " names, one per actuator, got " +
                                         std::to_string(names->size()));
    }
    for (std::size_t i = 0; i < names->size(); ++i) {
      if (!reading::is_plain_name((*names)[i])) {
        section.fail("actuator_names", "\"" + (*names)[i] + "\": a name is letters, digits, '_' and '-'");
      }
      for (std::size_t k = 0; k < i; ++k) {
        if ((*names)[k] == (*names)[i]) section.fail("actuator_names", "\"" + (*names)[i] + "\" is given twice");
      }
      c.actuator_names[i] = (*names)[i];
    }
  }
  return c;
}

void CommonSetupConfig::apply(PlanarGeometry& g) const {
  g.newton_tolerance_m = newton_tolerance_m;
  g.max_newton_iterations = max_newton_iterations;
  for (std::size_t i = 0; i < actuator_names.size(); ++i) {
    if (!actuator_names[i].empty()) g.actuators[i].name = actuator_names[i];
  }
}

std::string_view geometry_name(Geometry geometry) noexcept {
  return geometry == Geometry::kLargeDisplacement ? "large_displacement" : "linear";
}

SetupConfig read_setup_config(config::Source& section) {
  const std::string kind = section.choice("kind", SetupKinds::names(), "the experimental setup");
  const Geometry geometry =
      section.choice("geometry", {"linear", "large_displacement"},
                     "linear: the Jacobian at the reference configuration; large_displacement: the actuators' "
                     "lengths from the attachment points' displaced positions") == "large_displacement"
          ? Geometry::kLargeDisplacement
          : Geometry::kLinear;
  SetupConfig config = *SetupKinds::read(kind, section, geometry);
  section.finish();
  return config;
}

PlanarGeometry planar_geometry(const SetupConfig& config) {
  return std::visit([](const auto& p) { return p.planar(); }, config);
}

}  // namespace rpsd::setups
