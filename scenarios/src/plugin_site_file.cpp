#include "rpsd/scenarios/plugin_site_file.h"

#include "node_sections.h"
#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {
namespace node_sections {

void plugin_site_actuator(config::Source& a, node::PluginSiteEmulatorSetup& f) {
  // The UDP emulator's actuator section, one actuator per dof.
  node::ControllerEmulatorSetup actuator;
  emulator_actuator(a, actuator);
  f.plant = actuator.plant;
  f.initial_displacement_m = actuator.initial_displacement_m;
}

void plugin_site_file(config::Source& root, node::PluginSiteEmulatorSetup& f) {
  root.optional_text("description", "one line for titles");
  std::vector<std::unique_ptr<config::Source>> dofs;
  const auto site = root.section("plugin_site", "where the site listens, the node it serves, its control points");
  f.site = node::PluginSiteConfig::read(*site, dofs);
  const auto actuator = root.section("actuator", "the simulated actuators behind the dofs, in order");
  plugin_site_actuator(*actuator, f);
  root.finish();
  f.site.check(*site, dofs);
  if (static_cast<int>(f.initial_displacement_m.size()) != f.site.channels()) {
    actuator->fail("channels", "one per dof of the control points (" + std::to_string(f.site.channels()) + ")");
  }
}

}  // namespace node_sections

node::PluginSiteEmulatorSetup load_plugin_site_emulator(const std::filesystem::path& file,
                                                        const std::vector<Override>& overrides) {
  MappingReader root = load_root_reader(file, overrides);
  node::PluginSiteEmulatorSetup f;
  f.name = file.stem().string();
  node_sections::plugin_site_file(root, f);
  return f;
}

}  // namespace rpsd::scenarios
