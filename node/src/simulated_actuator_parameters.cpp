#include "rpsd/node/simulated_actuator_parameters.h"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/servo/coupled_specimen_actuator.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

namespace {

constexpr double kMaxCoupledEntry = 1e13;  // N/m and N s/m, as a specimen's stiffness

// The `planar` form of an experimental setup as its section gives it: its actuators' fixed
// ends and attachment points. Until setups::read_setup_config is implemented (branch
// geometry), which then replaces it. Read first and checked after (check()), so that a listing
// lists every key of the actuator's section.
struct PlanarSetupSection {
  std::unique_ptr<config::Source> section;
  std::vector<std::unique_ptr<config::Source>> actuators;
  std::optional<std::vector<std::string>> dofs;
  setups::PlanarGeometry geometry;
  std::vector<std::vector<double>> ends, attachments;

  explicit PlanarSetupSection(std::unique_ptr<config::Source> s) : section(std::move(s)) {
    config::Source& in = *section;
    in.choice("kind", {"planar"}, "the setup's kind (only planar here until the setup kinds are read)");
    geometry.geometry =
        in.choice_or("geometry", {"linear", "large_displacement"}, "linear",
                     "the strokes from the reference Jacobian, or from the displaced points") == "large_displacement"
            ? setups::Geometry::kLargeDisplacement
            : setups::Geometry::kLinear;
    dofs = in.optional_texts("dofs", "the DOFs in the site's order: translation_x, translation_y, rotation",
                             setups::kMaxSetupDofs);
    actuators = in.sections("actuators", setups::kMaxSetupDofs, "one per DOF, in the node's channels");
    const config::Number coordinate = config::Number::between(-1e3, 1e3, "m", "x and y in the lab's frame");
    for (std::size_t i = 0; i < actuators.size(); ++i) {
      config::Source& a = *actuators[i];
      geometry.actuators[i].name = a.optional_text("name", "for records and messages").value_or("");
      ends.push_back(a.numbers("fixed_end_m", coordinate, 2));
      attachments.push_back(a.numbers("attachment_m", coordinate, 2));
      a.finish();
    }
    in.finish();
  }

  // The geometry, checked as a PlanarSetup checks it; errors at their keys.
  setups::PlanarGeometry check() {
    config::Source& in = *section;
    for (std::size_t i = 0; i < actuators.size(); ++i) {
      if (ends[i].size() != 2) actuators[i]->fail("fixed_end_m", "needs two coordinates, x and y");
      if (attachments[i].size() != 2) actuators[i]->fail("attachment_m", "needs two coordinates, x and y");
      geometry.actuators[i].fixed_end_m = {ends[i][0], ends[i][1]};
      geometry.actuators[i].attachment_m = {attachments[i][0], attachments[i][1]};
    }
    if (!dofs) in.fail("dofs", "missing: the DOFs the setup drives");
    if (dofs->size() != actuators.size()) in.fail("actuators", "needs one actuator per DOF in dofs");
    geometry.dof_count = static_cast<int>(dofs->size());
    for (std::size_t j = 0; j < dofs->size(); ++j) {
      const std::string& d = (*dofs)[j];
      if (d == "translation_x") {
        geometry.dofs[j] = setups::DofMotion::kTranslationX;
      } else if (d == "translation_y") {
        geometry.dofs[j] = setups::DofMotion::kTranslationY;
      } else if (d == "rotation") {
        geometry.dofs[j] = setups::DofMotion::kRotation;
      } else {
        in.fail("dofs", "'" + d + "' is none of translation_x, translation_y, rotation");
      }
    }
    try {
      const setups::PlanarSetup checked(geometry);
    } catch (const std::invalid_argument& e) {
      in.fail("actuators", e.what());
    }
    return geometry;
  }
};

Eigen::MatrixXd dense(const std::vector<std::vector<double>>& rows) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()),
                                            static_cast<Eigen::Index>(rows.empty() ? 0 : rows.front().size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < rows[i].size() && static_cast<Eigen::Index>(j) < m.cols(); ++j) {
      m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
    }
  }
  return m;
}

CoupledSpecimenParameters read_coupled_specimen(config::Source& section, int channels,
                                                const servo::PlantConfig& plant) {
  CoupledSpecimenParameters c;
  PlanarSetupSection setup(section.section("setup", "the experimental setup the channels' actuators form"));
  const auto stiffness =
      section.matrix("stiffness",
                     config::Number::between(0.0, kMaxCoupledEntry, "N/m, N/rad, N m/rad",
                                             "the specimen's stiffness over the setup's DOFs (rows, or a diagonal)"),
                     setups::kMaxSetupDofs);
  const auto damping = section.matrix(
      "damping",
      config::Number::between(0.0, kMaxCoupledEntry, "N s/m, N s/rad, N m s/rad",
                              "the specimen's damping over the setup's DOFs (rows, or a diagonal: zeros for none)"),
      setups::kMaxSetupDofs);
  section.finish();
  // A listing, whose has() says no to every key, lists on past the checks (its values are
  // placeholders); a file got here with its `setup`.
  if (!section.has("setup")) return c;
  c.geometry = setup.check();
  const auto dofs = static_cast<std::size_t>(c.geometry.dof_count);
  if (dofs != static_cast<std::size_t>(channels)) {
    section.fail("setup", "drives " + std::to_string(dofs) + " DOFs with as many actuators, the node has " +
                              std::to_string(channels) + " channels");
  }
  if (stiffness.size() != dofs) section.fail("stiffness", "needs one row per DOF of the setup");
  c.stiffness = dense(stiffness);
  if (damping.size() != dofs) section.fail("damping", "needs one row per DOF of the setup");
  c.damping = dense(damping);
  try {
    servo::coupled_plant_config(plant);
  } catch (const std::invalid_argument& e) {
    section.fail_section(e.what());
  }
  return c;
}

}  // namespace

SimulatedActuatorParameters SimulatedActuatorParameters::read(config::Source& section, int channels) {
  const double k =
      section.number_or("specimen_stiffness_n_per_m", 0.0,
                        config::Number::between(0.0, 1e13, "N/m", "the specimen the load cell sees: F = k x"));
  SimulatedActuatorParameters p{servo::read_plant_config(*section.section("servo", "each channel's plant"), k), {}};
  if (auto coupled = section.optional_section(
          "coupled_specimen",
          "one specimen coupling the DOFs of a setup whose actuators are the channels (each plant's own specimen "
          "then carries no stiffness or damping)")) {
    p.coupled_specimen = read_coupled_specimen(*coupled, channels, p.plant);
  }
  return p;
}

OwnedActuator SimulatedActuatorParameters::make(const SimulatedActuatorParameters& config, int channels) {
  OwnedActuator owned;
  if (config.coupled_specimen) {
    const CoupledSpecimenParameters& c = *config.coupled_specimen;
    owned.plants = servo::make_plants(servo::coupled_plant_config(config.plant), channels);
    owned.actuator = std::make_unique<servo::CoupledSpecimenActuator>(
        owned.plants.pointers, setups::PlanarSetup(c.geometry), c.stiffness, c.damping);
    return owned;
  }
  owned.plants = servo::make_plants(config.plant, channels);
  owned.actuator = std::make_unique<servo::SimulatedActuator>(owned.plants.pointers);
  return owned;
}

}  // namespace rpsd::node
