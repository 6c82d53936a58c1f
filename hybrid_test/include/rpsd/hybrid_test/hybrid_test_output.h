// Runs an `rpsd_test` scenario into an output folder: time_history.csv (written step by step
// while the test runs, so an aborted or crashed run keeps every step it took),
// reference_history.csv (perfect actuator), summary.json, effective-scenario.yaml and PNG
// plots. summary.json is written first as "running" and last with the outcome, each time
// whole (results_files.h): a run killed outright leaves "running", never an older outcome.
// Not real-time safe.
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_document.h"
#include "rpsd/hybrid_test/progress.h"

namespace rpsd::hybrid_test {

// Outcome of a whole run, for the exit code.
enum class RunResult {
  kCompleted,
  kStopped,            // a limit, a run-away, a link or node failure: the reason is in summary.json
  kResultsNotWritten,  // a write failed; what could be written says so
  kInterrupted,        // SIGINT or SIGTERM: stopped in order after the step under way
  kNotReady,           // no servo node answered for a site before the first step: nothing moved
};
// summary.json's "result": completed, stopped, results_not_written, interrupted or not_ready.
const char* result_name(RunResult result);

// The headline numbers of one run, for sweep tables.
struct TestHeadline {
  RunResult result = RunResult::kCompleted;
  std::string outcome;               // "completed", or why the test stopped
  double j2_percent = 0.0;           // channel 0
  double j4_percent = 0.0;           // first recorded DOF against the reference
  double peak_displacement_m = 0.0;  // first recorded DOF
  double reference_peak_displacement_m = 0.0;
  std::array<double, 9> benchmark{};  // J1-J9 (benchmark_criteria.h), NaN where the test has none
  // Channel 0's peaks, for the benchmark's constraints (ChannelCriteria).
  double peak_measured_m = 0.0;
  double peak_measured_force_n = 0.0;
  double peak_command_velocity_m_per_s = 0.0;
  double tracking_delay_ms = std::nan("");  // channel 0's signed delay (ChannelCriteria), NaN if none
};

// Where a case of a sweep or batch writes its HDF5 results: the study's results.h5, under the
// case's group (hdf5_output/hdf5_batch.h). Empty: a results.h5 of its own, in its folder.
struct CaseHdf5 {
  std::filesystem::path file;
  std::string group;  // the case's folder name: case_000, run_001
};

// `progress` (optional) hears of each phase (the test and its reference with their steps,
// then the plots), as case `case_number` of `cases` of a sweep. `stop_request`: as in
// hybrid_test::AssemblyOptions. The folder must be ready (prepare_results_folder).
TestHeadline run_test_into(const std::filesystem::path& dir, const TestDocument& file,
                           const hybrid_test::TestConfig& scenario, const ProgressSink& progress = {},
                           const std::atomic<bool>* stop_request = nullptr, std::size_t case_number = 1,
                           std::size_t cases = 1, const CaseHdf5& in_study = {});

// Runs every case of a sweep into dir/case_NN/ and writes the table across the cases
// (sweep.csv, summary.json, sweep.png): kStopped if any case stopped; an interruption or a
// failed write ends the sweep after the case under way.
RunResult run_sweep_into(const std::filesystem::path& dir, const TestDocument& file, const ProgressSink& progress = {},
                         const std::atomic<bool>* stop_request = nullptr);

// Redraws the plots of a finished test folder from its CSV files.
void plot_test(const std::filesystem::path& dir);

// Redraws every plot of any folder rpsd wrote: a test's from its CSV files, a sweep's cases
// and its own table, a study's (Figures 5-8) from the gnuplot scripts beside its PNGs. Returns
// the PNGs drawn; throws std::invalid_argument naming the folder if it holds none.
std::vector<std::filesystem::path> plot_folder(const std::filesystem::path& dir);

}  // namespace rpsd::hybrid_test
