// Runs a `monte_carlo:` scenario into an output folder: each run into run_NNN/ as `rpsd run`
// writes a test, then runs.csv (each run's drawn values, outcome, J1-J9 and the constraint
// peaks), statistics.csv and statistics.md (mean, standard deviation and extremes of each over
// the completed runs: a stopped or interrupted run's criteria are partial, kept in runs.csv and
// its own summary but left out, and summary.json counts them) and summary.json. Not real-time safe.
#pragma once

#include <atomic>
#include <filesystem>

#include "rpsd/hybrid_test/hybrid_test_document.h"
#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/hybrid_test/progress.h"

namespace rpsd::hybrid_test {

// kStopped if any run stopped (a run stopped by a limit is still a result, and the next one
// runs); an interruption or a failed write ends the batch after the run under way.
RunResult run_monte_carlo_into(const std::filesystem::path& dir, const TestDocument& file,
                               const ProgressSink& progress = {}, const std::atomic<bool>* stop_request = nullptr);

}  // namespace rpsd::hybrid_test
