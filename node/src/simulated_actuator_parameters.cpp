#include "rpsd/node/simulated_actuator_parameters.h"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/servo/coupled_specimen_actuator.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/setups/setup_kinds.h"

namespace rpsd::node {

namespace {

constexpr double kMaxCoupledEntry = 1e13;  // N/m and N s/m, as a specimen's stiffness

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
  // A listing (has() says no to every key) lists every key, the optional damping too.
  const bool listing = !section.has("setup");
  auto setup = section.section("setup", "the experimental setup the channels' actuators form (as a scenario's)");
  const setups::SetupConfig setup_config = setups::read_setup_config(*setup);
  const auto stiffness =
      section.matrix("stiffness_n_per_m",
                     config::Number::between(-kMaxCoupledEntry, kMaxCoupledEntry, "N/m, N/rad, N m/rad",
                                             "the specimen's stiffness over the setup's DOFs (rows, or a diagonal)"),
                     setups::kMaxSetupDofs);
  std::vector<std::vector<double>> damping;
  if (section.has("damping_n_s_per_m") || listing) {
    damping = section.matrix(
        "damping_n_s_per_m",
        config::Number::between(-kMaxCoupledEntry, kMaxCoupledEntry, "N s/m, N s/rad, N m s/rad",
                                "the specimen's damping over the setup's DOFs (rows, or a diagonal; default none)"),
        setups::kMaxSetupDofs);
  }
  section.finish();
  if (listing) return c;
  try {
    c.geometry = setups::planar_geometry(setup_config);
    (void)setups::PlanarSetup(c.geometry);
  } catch (const std::invalid_argument& e) {
    setup->fail("kind", e.what());
  }
  const auto dofs = static_cast<std::size_t>(c.geometry.dof_count);
  if (dofs != static_cast<std::size_t>(channels)) {
    section.fail("setup", "drives " + std::to_string(dofs) + " DOFs with as many actuators, the node has " +
                              std::to_string(channels) + " channels");
  }
  if (stiffness.size() != dofs) section.fail("stiffness_n_per_m", "needs one row per DOF of the setup");
  c.stiffness = dense(stiffness);
  if (!c.stiffness.isApprox(c.stiffness.transpose())) section.fail("stiffness_n_per_m", "must be symmetric");
  if (!damping.empty() && damping.size() != dofs)
    section.fail("damping_n_s_per_m", "needs one row per DOF of the setup");
  c.damping = damping.empty() ? Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(dofs), static_cast<Eigen::Index>(dofs))
                              : dense(damping);
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

std::string SimulatedActuatorParameters::control_mode_refusal(int channel, servo::ControlMode mode) const {
  if (mode != servo::ControlMode::kForce) return {};
  const OwnedActuator probe = make(*this, channel + 1);
  if (probe.actuator->controls_force(channel)) return {};
  return "its plant has no force loop (only servo_model has one, with controller.force_gain_v_per_n stated in its "
         "parameter file, and without converters)";
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
