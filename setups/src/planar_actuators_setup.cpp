// planar: any setup in the plane, from each actuator's fixed end and attachment point in the
// lab's frame (the control point at the origin at the reference configuration).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rpsd/config/closest_name.h"
#include "rpsd/setups/setup_kinds.h"
#include "setup_reading.h"

namespace rpsd::setups {

namespace {

std::optional<DofMotion> motion_named(std::string_view name) {
  for (const DofMotion m : {DofMotion::kTranslationX, DofMotion::kTranslationY, DofMotion::kRotation}) {
    if (dof_motion_name(m) == name) return m;
  }
  return std::nullopt;
}

}  // namespace

PlanarActuatorsParameters PlanarActuatorsParameters::read(config::Source& section, Geometry geometry) {
  const auto dof_names = section.optional_texts(
      "dofs", "the site's DOFs in its order, each translation_x, translation_y or rotation (required)", kMaxSetupDofs);
  struct Read {
    std::unique_ptr<config::Source> section;
    std::string name;
    std::vector<double> fixed_end, attachment;
  };
  std::vector<Read> actuators;
  for (auto& s : section.sections("actuators", kMaxSetupDofs, "one per DOF, in any order: its two pins")) {
    Read a;
    a.name = s->text("name", "the actuator's name in records and messages");
    a.fixed_end = s->numbers("fixed_end_m", reading::coordinate("[x, y] of its pin on the reaction frame"), 2);
    a.attachment = s->numbers(
        "attachment_m", reading::coordinate("[x, y] of its pin on the specimen, at the reference configuration"), 2);
    s->finish();
    a.section = std::move(s);
    actuators.push_back(std::move(a));
  }
  const CommonSetupConfig common = CommonSetupConfig::read(section, static_cast<int>(actuators.size()), false);

  // Every key is read: now whether they fit together.
  PlanarActuatorsParameters p;
  p.geometry.geometry = geometry;
  if (!dof_names) section.fail("dofs", "required key is missing: the DOFs the actuators drive, e.g. [translation_x]");
  std::vector<std::string_view> known;
  for (const DofMotion m : {DofMotion::kTranslationX, DofMotion::kTranslationY, DofMotion::kRotation}) {
    known.push_back(dof_motion_name(m));
  }
  for (std::size_t i = 0; i < dof_names->size(); ++i) {
    const auto motion = motion_named((*dof_names)[i]);
    if (!motion) {
      section.fail("dofs", "\"" + (*dof_names)[i] + "\" is no DOF; expected " + config::listed(known) +
                               config::did_you_mean((*dof_names)[i], known));
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (p.geometry.dofs[k] == *motion) section.fail("dofs", "\"" + (*dof_names)[i] + "\" is given twice");
    }
    p.geometry.dofs[i] = *motion;
  }
  p.geometry.dof_count = static_cast<int>(dof_names->size());
  if (actuators.size() != dof_names->size()) {
    section.fail("actuators", "expected " + std::to_string(dof_names->size()) + " actuators, one per DOF, got " +
                                  std::to_string(actuators.size()));
  }
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    Read& a = actuators[i];
    reading::require_count(*a.section, "fixed_end_m", a.fixed_end, 2);
    reading::require_count(*a.section, "attachment_m", a.attachment, 2);
    if (!reading::is_plain_name(a.name)) {
      a.section->fail("name", "\"" + a.name + "\": a name is letters, digits, '_' and '-'");
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (actuators[k].name == a.name) a.section->fail("name", "\"" + a.name + "\" is given twice");
    }
    PlanarActuator& out = p.geometry.actuators[i];
    out.name = a.name;
    out.fixed_end_m = {a.fixed_end[0], a.fixed_end[1]};
    out.attachment_m = {a.attachment[0], a.attachment[1]};
    if (out.fixed_end_m == out.attachment_m) {
      a.section->fail("attachment_m", "the same point as fixed_end_m: an actuator of zero length");
    }
  }
  common.apply(p.geometry);
  reading::require_valid(section, "actuators", p.geometry);
  return p;
}

}  // namespace rpsd::setups
