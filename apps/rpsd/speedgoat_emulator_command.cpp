// `rpsd speedgoat-emulator TARGET.yaml`: a Speedgoat target running OpenFresco's hybrid
// controller model, in software, with simulated plants behind it, so that a node file of kind
// openfresco_speedgoat can be rehearsed with no hardware (docs/lab-controllers.md). Serves
// until SIGINT/SIGTERM (or --duration) and writes what it did (--summary).
#include <fstream>
#include <iostream>
#include <memory>

#include "rpsd/commands.h"
#include "rpsd/node/speedgoat_emulator_process.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "stop_signals.h"

namespace rpsd::cli {

void add_speedgoat_emulator(CLI::App& app) {
  struct Options {
    std::string config;
    std::vector<std::string> overrides;
    std::string summary;
    double duration_s = 0.0;
  };
  auto o = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "speedgoat-emulator", "Stand in for a Speedgoat target running OpenFresco's model (docs/lab-controllers.md)");
  command->add_option("config", o->config, "Emulator file (YAML)")->required()->check(CLI::ExistingFile);
  command->add_option("--set", o->overrides, "Override a key: key.path=value (repeatable)");
  command->add_option("--summary", o->summary, "Write what the emulator did (JSON) here when it stops");
  command->add_option("--duration", o->duration_s, "Stop after this many seconds (default: on SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  command->callback([o] {
    const auto setup = scenarios::load_speedgoat_emulator(o->config, parse_overrides(o->overrides));
    const auto& stop = stop_on_signals();
    const auto summary = node::emulate_speedgoat(setup, {o->duration_s}, stop, std::cout);
    if (!o->summary.empty()) std::ofstream(o->summary) << summary.dump(2) << '\n';
  });
}

}  // namespace rpsd::cli
