// The shape every serving command shares (`servo-node` and the three emulators): a YAML file,
// `--set` overrides, `--summary FILE.json` written when it stops, `--duration S`; the serve
// function reads the file, serves until a signal or the duration and returns the summary.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "rpsd/node/servo_node_process.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::cli {

using ServeFile = std::function<nlohmann::json(
    const std::string& file, const std::vector<scenarios::Override>& overrides, const node::ServeOptions& options)>;

// Looks at the summary once it is written (--summary) and throws for an exit code other than 0.
using CheckSummary = std::function<void(const nlohmann::json& summary)>;

void add_serving_command(CLI::App& app, const std::string& name, const std::string& description,
                         const std::string& file_help, ServeFile serve, CheckSummary check = {});

}  // namespace rpsd::cli
