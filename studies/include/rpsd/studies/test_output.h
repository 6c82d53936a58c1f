// Runs an `rpsd_test` scenario into an output folder: time_history.csv (written step by step
// while the test runs, so an aborted or crashed run keeps every step it took),
// reference_history.csv (perfect actuator), summary.json, effective-scenario.yaml and PNG
// plots. Not real-time safe.
#pragma once

#include <filesystem>
#include <functional>

#include "rpsd/studies/study_config.h"

namespace rpsd::studies {

// Outcome of a whole run, for the exit code.
enum class RunResult { kCompleted, kAborted };

// The headline numbers of one run, for sweep tables.
struct TestHeadline {
  RunResult result = RunResult::kCompleted;
  std::string outcome;               // "completed", or why the test stopped
  double j2_percent = 0.0;           // channel 0
  double j4_percent = 0.0;           // first recorded DOF against the reference
  double peak_displacement_m = 0.0;  // first recorded DOF
  double reference_peak_displacement_m = 0.0;
};

// `progress` (optional) receives (steps done, steps planned) while the test runs.
TestHeadline run_test_into(const std::filesystem::path& dir, const StudyDocument& file,
                           const coordinator::TestConfig& scenario,
                           const std::function<void(std::int64_t, std::int64_t)>& progress = {});

// Runs every case of a sweep into dir/case_NN/ and writes the table across the cases
// (sweep.csv, summary.json, sweep.png). kAborted if any case aborted.
RunResult run_sweep_into(const std::filesystem::path& dir, const StudyDocument& file,
                         const std::function<void(std::int64_t, std::int64_t)>& progress = {});

// Redraws the plots of a finished test folder from its CSV files.
void plot_test(const std::filesystem::path& dir);

}  // namespace rpsd::studies
