// The overrides of a run as the command line states them: `--set key.path=value` texts, and
// `--record`, `--telemetry`, `--format` and `--histories` as the keys they stand for.
#pragma once

#include <string>
#include <vector>

#include "rpsd/scenarios/study_file.h"

namespace rpsd::commands {

// `--set key.path=value` texts to overrides named "--set #N" (ConfigError on a malformed one).
std::vector<scenarios::Override> parse_overrides(const std::vector<std::string>& texts);

// What a run takes beside its scenario's keys (RunScenarioOptions).
struct RunOverrideOptions {
  std::string record;  // a PEER AT2 file replacing the scenario's record (its processing kept); "" none
  bool telemetry = false;
  std::string format;           // output.format: csv, hdf5 or both; "" the scenario's
  std::string histories;        // output.histories: all, criteria_only or decimated; "" the scenario's
  std::string history_rate_hz;  // output.history_rate_hz (the reader checks it); "" the scenario's
};

// `--record`, then `--telemetry`, `--format`, `--histories` and `--history-rate-hz`, then `set`
// in its order (later wins).
std::vector<scenarios::Override> run_overrides(const RunOverrideOptions& options,
                                               const std::vector<scenarios::Override>& set);

}  // namespace rpsd::commands
