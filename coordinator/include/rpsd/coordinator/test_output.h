// Runs an `rpsd_test` scenario into an output folder: time_history.csv (written step by step
// while the test runs, so an aborted or crashed run keeps every step it took),
// reference_history.csv (perfect actuator), summary.json, effective-scenario.yaml and PNG
// plots. Not real-time safe.
#pragma once

#include <filesystem>
#include <functional>

#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {

/// Outcome of a whole run, for the exit code.
enum class RunResult { kCompleted, kAborted };

/// `progress` (optional) receives (steps done, steps planned) while the test runs.
RunResult run_test_into(const std::filesystem::path& dir, const scenarios::StudyFile& file,
                        const scenarios::TestScenario& scenario,
                        const std::function<void(std::int64_t, std::int64_t)>& progress = {});

/// Redraws the plots of a finished test folder from its CSV files.
void plot_test(const std::filesystem::path& dir);

}  // namespace rpsd::coordinator
