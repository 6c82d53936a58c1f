// The pre-test check for a reader: its table (predicted peaks against each limit, damping
// per mode, the servo loop's gain margin, the verdict) and its numbers (dry-run.json).
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "rpsd/studies/dry_run.h"

namespace rpsd::studies {

// Writes the table to `out` and returns the numbers. Not real-time safe.
nlohmann::json report_dry_run(const DryRunReport& report, const std::string& test_name, std::ostream& out);

}  // namespace rpsd::studies
