#include "rpsd/commands/overrides.h"

#include <filesystem>

namespace rpsd::commands {

std::vector<scenarios::Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<scenarios::Override> overrides;
  for (const auto& t : texts) {
    overrides.push_back(scenarios::parse_override(t));
    overrides.back().origin = "--set #" + std::to_string(overrides.size());
  }
  return overrides;
}

std::vector<scenarios::Override> run_overrides(const RunOverrideOptions& options,
                                               const std::vector<scenarios::Override>& set) {
  // --record replaces the record and keeps the scenario's processing; --set may then refine it.
  std::vector<scenarios::Override> overrides;
  if (!options.record.empty()) {
    overrides.push_back({"ground_motion",
                         "{file: \"" + std::filesystem::absolute(options.record).string() + "\", format: peer_at2}",
                         "--record", scenarios::Override::Kind::kRecord});
  }
  if (options.telemetry) overrides.push_back({"output.telemetry", "true", "--telemetry"});
  if (!options.format.empty()) overrides.push_back({"output.format", options.format, "--format"});
  if (!options.histories.empty()) overrides.push_back({"output.histories", options.histories, "--histories"});
  if (!options.history_rate_hz.empty()) {
    overrides.push_back({"output.history_rate_hz", options.history_rate_hz, "--history-rate-hz"});
  }
  overrides.insert(overrides.end(), set.begin(), set.end());
  return overrides;
}

}  // namespace rpsd::commands
