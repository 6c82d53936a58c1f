// `rpsd run SCENARIO --dry-run [--node NODE.yaml ...]`: the pre-test check of a test scenario
// against its own limits and those of its servo nodes' files. Not real-time safe.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "rpsd/scenarios/study_file.h"

namespace rpsd::commands {

struct DryRunCheck {
  nlohmann::json report;  // as dry-run.json and `--dry-run --json` have it
  bool ready = false;     // within every limit (report["ready"])
};

// Writes the table to `table` and returns the numbers. ConfigError when the file is not an
// `rpsd_test` scenario (a study) or a node file is bad.
DryRunCheck dry_run_check(const studies::StudyDocument& file, const std::vector<std::string>& node_files,
                          std::ostream& table);

}  // namespace rpsd::commands
