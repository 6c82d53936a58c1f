// `rpsd plugin-site-emulator SITE.yaml`: a NEES/LabVIEW plugin site in software, so that a lab
// can rehearse a `nees_plugin` node file with no hardware (docs/lab-controllers.md). Reads the
// file, serves until SIGINT/SIGTERM (or --duration), writes the summary.
#include <fstream>
#include <iostream>
#include <memory>

#include "rpsd/commands.h"
#include "rpsd/node/nees_plugin_site_process.h"
#include "rpsd/scenarios/plugin_site_file.h"
#include "stop_signals.h"

namespace rpsd::cli {

void add_plugin_site_emulator(CLI::App& app) {
  struct Options {
    std::string config;
    std::vector<std::string> overrides;
    std::string summary;
    double duration_s = 0.0;
  };
  auto o = std::make_shared<Options>();
  auto* command = app.add_subcommand("plugin-site-emulator",
                                     "Stand in for a NEES/LabVIEW plugin site on TCP (docs/lab-controllers.md)");
  command->add_option("config", o->config, "Configuration file (YAML)")->required()->check(CLI::ExistingFile);
  command->add_option("--set", o->overrides, "Override a key: key.path=value (repeatable)");
  command->add_option("--summary", o->summary, "Write what the site did (JSON) here when it stops");
  command->add_option("--duration", o->duration_s, "Stop after this many seconds (default: on SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  command->callback([o] {
    const auto setup = scenarios::load_plugin_site_emulator(o->config, parse_overrides(o->overrides));
    const std::atomic<bool>& stop = stop_on_signals();
    const nlohmann::json summary = node::emulate_plugin_site(setup, {o->duration_s}, stop, std::cout);
    if (!o->summary.empty()) std::ofstream(o->summary) << summary.dump(2) << '\n';
  });
}

}  // namespace rpsd::cli
