#include "rpsd/scenarios/plugin_site_file.h"

#include "node_sections.h"
#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {
namespace node_sections {

void plugin_site_actuator(config::Source& a, node::PluginSiteEmulatorSetup& f) {
  // The UDP emulator's actuator section, one actuator per dof.
  node::ControllerEmulatorSetup actuator;
  emulator_actuator(a, actuator);
  if (actuator.channels != f.site.channels()) {
    a.fail("channels", "one per dof of the control points (" + std::to_string(f.site.channels()) + ")");
  }
  f.plant = actuator.plant;
  f.initial_displacement_m = actuator.initial_displacement_m;
}

void plugin_site_file(config::Source& root, node::PluginSiteEmulatorSetup& f) {
  root.optional_text("description", "one line for titles");
  f.site = node::PluginSiteConfig::read(
      *root.section("plugin_site", "where the site listens, the node it serves, its control points"));
  plugin_site_actuator(*root.section("actuator", "the simulated actuators behind the dofs, in order"), f);
  root.finish();
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
