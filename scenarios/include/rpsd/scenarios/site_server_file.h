// The file of `rpsd site-server` (see examples/opensees/*.yaml): where the server listens,
// the OpenSees element's basic DOFs and the channel that follows each, and the experimental
// half of a test with the keys of a test scenario (experimental[] with basic_dof instead of
// dof, servo, compensation, clock, transport).
#pragma once

#include <filesystem>
#include <vector>

#include "rpsd/scenarios/study_file.h"
#include "rpsd/site_server/site_server_config.h"

namespace rpsd::scenarios {

// A site-server file has `listen:` and no `study:` (ConfigError if it cannot be read as YAML).
bool is_site_server_file(const std::filesystem::path& file);

// Throws ConfigError naming file:line:column and the key path. Not real-time safe.
site_server::SiteServerConfig load_site_server(const std::filesystem::path& file,
                                               const std::vector<Override>& overrides = {});

}  // namespace rpsd::scenarios
