// The sections of a servo node's file, of a controller emulator's and of a plugin site
// emulator's, each read from a config::Source: the file readers (servo_node_file.cpp,
// plugin_site_file.cpp) compose them, and the scenario reference lists their keys by running
// each on a config::KeyTable.
#pragma once

#include <filesystem>
#include <memory>

#include "rpsd/config/source.h"
#include "rpsd/node/nees_plugin_site_process.h"
#include "rpsd/node/servo_node_setup.h"
#include "rpsd/node/speedgoat_emulator_process.h"

namespace rpsd::scenarios::node_sections {

void node(config::Source& n, node::ServoNodeSetup& f);
void dds(config::Source& d, const std::filesystem::path& dir, node::ServoNodeSetup& f);
void actuator(config::Source& a, node::ServoNodeSetup& f);
void limits(config::Source& l, node::ServoNodeSetup& f);
void watchdog(config::Source& w, node::ServoNodeSetup& f);

// The whole file: its own keys, then its sections. Returns the `limits` section, if any (the
// envelope's check names its keys).
std::unique_ptr<config::Source> node_file(config::Source& root, const std::filesystem::path& dir,
                                          node::ServoNodeSetup& f);
void emulator_file(config::Source& root, node::ControllerEmulatorSetup& f);

void emulator_udp(config::Source& u, node::ControllerEmulatorSetup& f);
void emulator_actuator(config::Source& a, node::ControllerEmulatorSetup& f);

// The file of `rpsd plugin-site-emulator` (plugin_site_file.cpp).
void plugin_site_file(config::Source& root, node::PluginSiteEmulatorSetup& f);
void plugin_site_actuator(config::Source& a, node::PluginSiteEmulatorSetup& f);
// `rpsd speedgoat-emulator`'s file: `actuator` (as the controller emulator's), then `target`.
void speedgoat_emulator_file(config::Source& root, node::SpeedgoatEmulatorSetup& f);

}  // namespace rpsd::scenarios::node_sections
