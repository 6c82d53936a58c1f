#include "rpsd/node/actuator_factory.h"

#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

OwnedActuator make_actuator(const ActuatorConfig& config, int channels) {
  OwnedActuator owned;
  if (const auto* simulated = std::get_if<SimulatedActuatorConfig>(&config)) {
    owned.plants = servo::make_plants(simulated->plant, channels);
    owned.actuator = std::make_unique<servo::SimulatedActuator>(owned.plants.pointers);
  } else {
    owned.actuator = std::make_unique<UdpControllerActuator>(std::get<UdpControllerConfig>(config));
  }
  return owned;
}

}  // namespace rpsd::node
