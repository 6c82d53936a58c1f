// `rpsd plugin-site-emulator SITE.yaml`: a NEES/LabVIEW plugin site in software, so that a lab
// can rehearse a `nees_plugin` node file with no hardware (docs/lab-controllers.md). Reads the
// file, serves until SIGINT/SIGTERM (or --duration), writes the summary.
#include <iostream>

#include "rpsd/commands.h"
#include "rpsd/node/nees_plugin_site_process.h"
#include "rpsd/scenarios/plugin_site_file.h"
#include "serving_command.h"
#include "stop_signals.h"

namespace rpsd::cli {

void add_plugin_site_emulator(CLI::App& app) {
  add_serving_command(app, "plugin-site-emulator",
                      "Stand in for a NEES/LabVIEW plugin site on TCP (docs/lab-controllers.md)",
                      "Configuration file (YAML)", [](const auto& file, const auto& overrides, const auto& options) {
                        const auto setup = scenarios::load_plugin_site_emulator(file, overrides);
                        return node::emulate_plugin_site(setup, options, stop_on_signals(), std::cout);
                      });
}

}  // namespace rpsd::cli
