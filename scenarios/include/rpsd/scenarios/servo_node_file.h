// The configuration file of `rpsd servo-node` (see examples/nodes/*.yaml): which test and
// site the node serves, how it is paced, its actuator (a simulated plant or a UDP
// controller), its own limits and what it does when commands stop. And the file of
// `rpsd controller-emulator`, which stands in for a hardware controller.
#pragma once

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "rpsd/realtime/realtime_setup.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/scenarios/test_scenario.h"
#include "rpsd/servo/servo_node_config.h"
#include "rpsd/servo/udp_controller_actuator.h"
#include "rpsd/transport/dds_participant.h"

namespace rpsd::scenarios {

/// Simulated actuators: one plant per channel, all of the same kind.
struct SimulatedActuatorSection {
  PlantConfig plant;
};

struct ServoNodeFile {
  std::string name;
  enum class Mode {
    kRealTime,  ///< paced at control_rate_hz; the newest command is applied on each tick
    kLockStep,  ///< one control period per command, as fast as commands come (rehearsals over DDS)
  };
  Mode mode = Mode::kRealTime;
  servo::ServoNodeConfig node;
  std::vector<double> initial_displacement_m;  ///< one per channel
  std::variant<SimulatedActuatorSection, servo::UdpControllerConfig> actuator;
  transport::DdsDomainConfig dds;
  realtime::RealTimeRequest realtime;
  double heartbeat_rate_hz = 10.0;
};

/// Throws ConfigError naming file:line:column and the key path.
ServoNodeFile load_servo_node(const std::filesystem::path& file, const std::vector<Override>& overrides = {});

struct ControllerEmulatorFile {
  std::string name;
  std::string bind_host = "127.0.0.1";
  std::uint16_t port = 0;
  int channels = 1;
  PlantConfig plant;
  std::vector<double> initial_displacement_m;
};

ControllerEmulatorFile load_controller_emulator(const std::filesystem::path& file, const std::vector<Override>& overrides = {});

}  // namespace rpsd::scenarios
