// The body of `rpsd speedgoat-emulator FILE.yaml`: the emulated target of a Speedgoat node
// file, with its simulated plants, served until stopped, and what it did (the --summary JSON).
#pragma once

#include <atomic>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rpsd/node/servo_node_process.h"
#include "rpsd/node/speedgoat_emulator.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::node {

struct SpeedgoatEmulatorSetup {
  std::string name;
  SpeedgoatEmulatorConfig target;  // where it listens, its node, its signal order and scales
  int channels = 1;
  servo::PlantConfig plant;
  std::vector<double> initial_displacement_m;
};

// Serves until `stop` or the duration; progress lines go to `log`. Not real-time safe.
nlohmann::json emulate_speedgoat(const SpeedgoatEmulatorSetup& setup, const ServeOptions& options,
                                 const std::atomic<bool>& stop, std::ostream& log);

}  // namespace rpsd::node
