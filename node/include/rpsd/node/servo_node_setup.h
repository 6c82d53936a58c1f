// Everything one `rpsd servo-node` process needs, as read from its node file (scenarios/
// reads the file into it): which test and site it serves, how it is paced, its actuator, its
// own limits and watchdog, and its DDS domain. And the setup of `rpsd controller-emulator`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rpsd/node/actuator_factory.h"
#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/servo_node_config.h"
#include "rpsd/realtime/realtime_setup.h"
#include "rpsd/transport/dds_participant.h"

namespace rpsd::node {

struct ServoNodeSetup {
  std::string name;  // the node file's stem, for messages and the summary
  enum class Mode : std::uint8_t {
    kRealTime,  // paced at the control rate; the newest command is applied on each tick
    kLockStep,  // one control period per command, as fast as commands come (rehearsals over DDS)
  };
  Mode mode = Mode::kRealTime;
  ServoNodeConfig node;
  std::vector<double> initial_displacement_m;  // one per channel
  ActuatorConfig actuator;
  transport::DdsDomainConfig dds;
  realtime::RealTimeRequest realtime;
  double heartbeat_rate_hz = 10.0;
};

struct ControllerEmulatorSetup {
  std::string name;
  ControllerEmulatorConfig udp;  // where it listens, its node, the protocol and key
  int channels = 1;
  servo::PlantConfig plant;
  std::vector<double> initial_displacement_m;
};

}  // namespace rpsd::node
