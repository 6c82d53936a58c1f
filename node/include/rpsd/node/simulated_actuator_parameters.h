// Simulated actuators behind a servo node: one plant per channel, all of one configuration
// (the node's `actuator: {kind: simulated}`).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/node/owned_actuator.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/setups/planar_setup.h"

namespace rpsd::node {

// One specimen whose restoring forces couple the DOFs an experimental setup drives, carried by
// the node's simulated actuators (servo/coupled_specimen_actuator.h): the node's channel i is
// the setup's actuator i, and the plants' own specimens carry no stiffness or damping.
struct CoupledSpecimenParameters {
  setups::PlanarGeometry geometry;     // the setup's (actuator.coupled_specimen.setup)
  Eigen::MatrixXd stiffness, damping;  // over the setup's DOFs (N/m, N/rad, N m/rad)
};

struct SimulatedActuatorParameters {
  static constexpr std::string_view kName = "simulated";
  static constexpr std::string_view kSummary = "simulated plants, one per channel, in the node's process";
  // `specimen_stiffness_n_per_m` (the load cell's k), the `servo` plant section and, when the
  // channels are a setup's actuators, `coupled_specimen`.
  static SimulatedActuatorParameters read(config::Source& section, int channels);
  // Not real-time safe.
  static OwnedActuator make(const SimulatedActuatorParameters& config, int channels);
  servo::Envelope envelope() const { return servo::envelope_of(plant); }
  // Why channel `channel` cannot be in `mode` (empty: it can): in force control, its plant has
  // no force loop. Not real-time safe.
  std::string control_mode_refusal(int channel, servo::ControlMode mode) const;

  servo::PlantConfig plant;
  std::optional<CoupledSpecimenParameters> coupled_specimen;
};
using SimulatedActuatorConfig [[deprecated("renamed SimulatedActuatorParameters (docs/migration.md)")]] =
    SimulatedActuatorParameters;

}  // namespace rpsd::node
