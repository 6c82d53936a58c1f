// The body of `rpsd plugin-site-emulator`: a NEES/LabVIEW plugin site in software, serving
// until stopped, then saying what it did (the --summary JSON). The command line only reads
// the file (scenarios/), handles signals and writes the summary. Not real-time safe.
#pragma once

#include <atomic>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rpsd/node/nees_plugin_site_emulator.h"
#include "rpsd/node/servo_node_process.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::node {

struct PluginSiteEmulatorSetup {
  std::string name;
  PluginSiteConfig site;                       // where it listens, its node, its control points
  servo::PlantConfig plant;                    // the simulated actuator behind every dof
  std::vector<double> initial_displacement_m;  // one per dof, SI
};

nlohmann::json emulate_plugin_site(const PluginSiteEmulatorSetup& setup, const ServeOptions& options,
                                   const std::atomic<bool>& stop, std::ostream& log);

}  // namespace rpsd::node
