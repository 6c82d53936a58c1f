// The file of `rpsd plugin-site-emulator` (examples/nodes/plugin-site-emulator.yaml): a
// NEES/LabVIEW plugin site in software, its control points and the simulated actuators behind
// them.
#pragma once

#include <filesystem>
#include <vector>

#include "rpsd/node/nees_plugin_site_process.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::scenarios {

// Throws ConfigError naming file:line:column and the key path.
node::PluginSiteEmulatorSetup load_plugin_site_emulator(const std::filesystem::path& file,
                                                        const std::vector<Override>& overrides = {});

}  // namespace rpsd::scenarios
