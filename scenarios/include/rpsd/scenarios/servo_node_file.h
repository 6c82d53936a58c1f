// The configuration file of `rpsd servo-node` (see examples/nodes/*.yaml): which test and
// site the node serves, how it is paced, its actuator (a simulated plant or a UDP
// controller), its own limits and what it does when commands stop. And the file of
// `rpsd controller-emulator`, which stands in for a hardware controller, and of
// `rpsd speedgoat-emulator`, which stands in for a Speedgoat target (docs/lab-controllers.md).
#pragma once

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "rpsd/node/servo_node_setup.h"
#include "rpsd/node/speedgoat_emulator_process.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::scenarios {

// Throws ConfigError naming file:line:column and the key path.
node::ServoNodeSetup load_servo_node(const std::filesystem::path& file, const std::vector<Override>& overrides = {});

// A servo node's file (top-level `node` and `actuator`, no `study`): what `rpsd validate`
// checks as one. Throws ConfigError for a file that is not YAML.
bool is_servo_node_file(const std::filesystem::path& file);

node::ControllerEmulatorSetup load_controller_emulator(const std::filesystem::path& file,
                                                       const std::vector<Override>& overrides = {});

node::SpeedgoatEmulatorSetup load_speedgoat_emulator(const std::filesystem::path& file,
                                                     const std::vector<Override>& overrides = {});

}  // namespace rpsd::scenarios
