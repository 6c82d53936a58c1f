// `rpsd run SCENARIO --out DIR`: the scenario read with its overrides, the folder prepared,
// the study run and written (studies::run_and_write). The command line and the Python module
// run a scenario through these, so a run from Python writes what the command line writes.
// Not real-time safe.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>

#include "rpsd/hybrid_test/external_parts.h"
#include "rpsd/hybrid_test/progress.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/studies/study_output.h"

namespace rpsd::commands {

// Reads the scenario with its overrides (run_overrides). ConfigError names the file, line,
// column and key. `external`: the parts a host program gives for `kind: external`
// (the Python module's callables; none from the command line).
studies::StudyDocument load_run_scenario(const std::filesystem::path& scenario,
                                         const std::vector<scenarios::Override>& overrides,
                                         const hybrid_test::ExternalParts& external = {});

// An `rpsd_test` without a sweep or a Monte Carlo batch: the one kind that writes results.h5.
bool is_single_test(const studies::StudyDocument& file);

struct ScenarioRunOptions {
  std::filesystem::path out;  // created if missing; refused if it holds anything
  bool replace = false;       // clear a folder an earlier rpsd run wrote
  // false: the caller prepared `out` itself (prepare_results_folder), and may have put the
  // scenario it runs there first (rpsd.run with a dict).
  bool prepare = true;
  hybrid_test::ProgressSink progress;
  // Set by whoever asks the run to stop in order (a signal handler, Ctrl-C in Python); tests,
  // sweeps and batches stop after the step under way, the servo studies run to their end.
  const std::atomic<bool>* stop_request = nullptr;
};

// Prepares `out` and runs the study into it. The outcome is in the result (throw_unless_completed).
studies::StudyRun run_scenario(const studies::StudyDocument& file, const ScenarioRunOptions& options);

}  // namespace rpsd::commands
