// Writes a study's results into an output folder: time histories and tables as CSV,
// DIR/summary.json, and PNG plots like the seed paper's figures. Not real-time safe.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/hybrid_test/progress.h"
#include "rpsd/studies/servo_studies.h"

namespace rpsd::studies {

void write_sine_sweep(const std::filesystem::path& dir, const StudyDocument& file, const SineSweepStudy& study,
                      const SineSweepResult& result);

void write_frequency_response(const std::filesystem::path& dir, const StudyDocument& file,
                              const FrequencyResponseStudy& study, const std::vector<FrequencyResponseRow>& rows);

void write_max_gain(const std::filesystem::path& dir, const StudyDocument& file, const MaxGainStudy& study,
                    const std::vector<MaxGainRow>& rows);

struct StudyRun {
  hybrid_test::RunResult result = hybrid_test::RunResult::kCompleted;
  std::string reason;  // why an `rpsd_test` run did not complete (as in its summary.json)
  // Where the steps taken are recorded: a test's time_history.csv, or for a sweep or a Monte
  // Carlo batch that did not complete the time histories of its cases that did not (files that
  // exist; a batch folder has none of its own).
  std::string recorded_in;
};

// Runs whichever study the file holds and writes it into dir (created if missing; the
// command line first makes sure it is empty: prepare_results_folder). A test that stopped still has every step it took
// on disk. `stop_request` (optional): set by a signal handler to end a test or sweep in order.
StudyRun run_and_write(const StudyDocument& file, const std::filesystem::path& dir,
                       const hybrid_test::ProgressSink& progress = {}, const std::atomic<bool>* stop_request = nullptr);

}  // namespace rpsd::studies
