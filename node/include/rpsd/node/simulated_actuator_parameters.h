// Simulated actuators behind a servo node: one plant per channel, all of one configuration
// (the node's `actuator: {kind: simulated}`).
#pragma once

#include <string>
#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/node/owned_actuator.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::node {

struct SimulatedActuatorParameters {
  static constexpr std::string_view kName = "simulated";
  static constexpr std::string_view kSummary = "simulated plants, one per channel, in the node's process";
  // `specimen_stiffness_n_per_m` (the load cell's k) and the `servo` plant section.
  static SimulatedActuatorParameters read(config::Source& section, int channels);
  // Not real-time safe.
  static OwnedActuator make(const SimulatedActuatorParameters& config, int channels);
  servo::Envelope envelope() const { return servo::envelope_of(plant); }
  // Why channel `channel` cannot be in `mode` (empty: it can): in force control, its plant has
  // no force loop. Not real-time safe.
  std::string control_mode_refusal(int channel, servo::ControlMode mode) const;

  servo::PlantConfig plant;
};
using SimulatedActuatorConfig [[deprecated("renamed SimulatedActuatorParameters (docs/migration.md)")]] =
    SimulatedActuatorParameters;

}  // namespace rpsd::node
