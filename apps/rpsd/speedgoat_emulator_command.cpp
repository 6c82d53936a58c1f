// `rpsd speedgoat-emulator TARGET.yaml`: a Speedgoat target running OpenFresco's hybrid
// controller model, in software, with simulated plants behind it, so that a node file of kind
// openfresco_speedgoat can be rehearsed with no hardware (docs/lab-controllers.md). Serves
// until SIGINT/SIGTERM (or --duration) and writes what it did (--summary).
#include <iostream>

#include "rpsd/commands.h"
#include "rpsd/node/speedgoat_emulator_process.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "serving_command.h"
#include "stop_signals.h"

namespace rpsd::cli {

void add_speedgoat_emulator(CLI::App& app) {
  add_serving_command(app, "speedgoat-emulator",
                      "Stand in for a Speedgoat target running OpenFresco's model (docs/lab-controllers.md)",
                      "Emulator file (YAML)", [](const auto& file, const auto& overrides, const auto& options) {
                        const auto setup = scenarios::load_speedgoat_emulator(file, overrides);
                        return node::emulate_speedgoat(setup, options, stop_on_signals(), std::cout);
                      });
}

}  // namespace rpsd::cli
