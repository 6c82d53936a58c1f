// `rpsd validate FILE [--set ...]`: a scenario, a site-server file or a servo node's file read
// and checked without running anything, as text for a person or as JSON for a program
// (`--json`, rpsd.validate in Python). Both come from one reading of the file. Not real-time safe.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "rpsd/scenarios/study_file.h"

namespace rpsd::commands {

// Reads and checks the file (ConfigError naming file, line, column and key), writes the text
// overview to `text` and returns the same as JSON: "file", "kind" (rpsd_test, sweep,
// monte_carlo, study, site_server or servo_node), the kind's own fields, and "overview" (the text's lines).
// `external`: a host program's parts for a scenario's `kind: external` (none from the command line).
nlohmann::json validate_file(const std::filesystem::path& file, const std::vector<scenarios::Override>& overrides,
                             std::ostream& text, const hybrid_test::ExternalParts& external = {});

}  // namespace rpsd::commands
