// The actuators a servo node can drive, registered in one place (the list below): a new
// adapter is its own files (an Actuator, and a config naming itself with kName, reading its
// keys with read() and building the actuator with make()) plus one entry here
// (CONTRIBUTING.md).
#pragma once

#include <string>

#include "rpsd/config/kind_list.h"
#include "rpsd/node/nees_plugin_actuator.h"
#include "rpsd/node/owned_actuator.h"
#include "rpsd/node/simulated_actuator_parameters.h"
#include "rpsd/node/speedgoat_actuator.h"
#include "rpsd/node/udp_controller_actuator.h"

namespace rpsd::node {

using ActuatorKinds =
    config::KindList<SimulatedActuatorParameters, UdpControllerParameters, SpeedgoatParameters, NeesPluginParameters>;
using ActuatorConfig = ActuatorKinds::Variant;

// Builds the actuator for `channels` channels. Not real-time safe; throws
// std::invalid_argument naming what does not fit.
inline OwnedActuator make_actuator(const ActuatorConfig& config, int channels) {
  return std::visit([channels](const auto& c) { return std::decay_t<decltype(c)>::make(c, channels); }, config);
}

// Why channel `channel` of this actuator cannot be in control mode `mode` (empty: it can). Not
// real-time safe.
inline std::string control_mode_refusal(const ActuatorConfig& config, int channel, servo::ControlMode mode) {
  return std::visit([channel, mode](const auto& c) { return c.control_mode_refusal(channel, mode); }, config);
}

// What the actuator's rig can do: the simulated plant's envelope, or the one a hardware
// adapter's file states.
inline servo::Envelope envelope_of(const ActuatorConfig& config) {
  return std::visit([](const auto& c) { return c.envelope(); }, config);
}

}  // namespace rpsd::node
