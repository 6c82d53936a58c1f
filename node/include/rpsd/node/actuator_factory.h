// The actuators a servo node can drive, in one place: simulated plants (one per channel) or
// a hardware controller on UDP. A new adapter is its own files (an servo::Actuator) plus one
// alternative here and one branch in actuator_factory.cpp (CONTRIBUTING.md).
#pragma once

#include <memory>
#include <variant>

#include "rpsd/node/udp_controller_actuator.h"
#include "rpsd/servo/actuator.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::node {

// Simulated actuators: one plant per channel, all of one configuration.
struct SimulatedActuatorConfig {
  servo::PlantConfig plant;
};

using ActuatorConfig = std::variant<SimulatedActuatorConfig, UdpControllerConfig>;

// The actuator and whatever it borrows (the simulated plants), owned together.
struct OwnedActuator {
  servo::PlantSet plants;
  std::unique_ptr<servo::Actuator> actuator;
};

// Builds the actuator for `channels` channels. Not real-time safe; throws
// std::invalid_argument naming what does not fit.
OwnedActuator make_actuator(const ActuatorConfig& config, int channels);

}  // namespace rpsd::node
