#include "rpsd/node/simulated_actuator_parameters.h"

#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

SimulatedActuatorParameters SimulatedActuatorParameters::read(config::Source& section, int) {
  const double k =
      section.number_or("specimen_stiffness_n_per_m", 0.0,
                        config::Number::between(0.0, 1e13, "N/m", "the specimen the load cell sees: F = k x"));
  return {servo::read_plant_config(*section.section("servo", "each channel's plant"), k)};
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
  owned.plants = servo::make_plants(config.plant, channels);
  owned.actuator = std::make_unique<servo::SimulatedActuator>(owned.plants.pointers);
  return owned;
}

}  // namespace rpsd::node
