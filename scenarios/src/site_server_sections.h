// The sections of a site-server file, each read from a config::Source: the file's reader
// (site_server_file.cpp) composes them, and the scenario reference lists their keys.
#pragma once

#include <memory>

#include "rpsd/config/source.h"
#include "rpsd/site_server/site_server_config.h"

namespace rpsd::scenarios::site_server_sections {

// The whole file but for its check against the rig (load_site_server does that).
void site_file(config::Source& root, site_server::SiteServerConfig& c,
               std::vector<std::unique_ptr<config::Source>>& limit_sections);
void listen(config::Source& l, site_server::SiteServerConfig& c);
// experimental[i]: a test's channel keys, with basic_dof and relative_to for dof.
hybrid_test::ExperimentalChannel channel(config::Source& e, int dofs, std::size_t index, site_server::ChannelMap& map,
                                         std::unique_ptr<config::Source>& limits_section);

}  // namespace rpsd::scenarios::site_server_sections
