// Writes a study's results into an output folder: time histories and tables as CSV,
// DIR/summary.json, and PNG plots like the seed paper's figures. Not real-time safe.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rpsd/studies/servo_studies.h"

namespace rpsd::studies {

void write_sine_sweep(const std::filesystem::path& dir, const StudyDocument& file, const SineSweepStudy& study,
                      const SineSweepResult& result);

void write_frequency_response(const std::filesystem::path& dir, const StudyDocument& file,
                              const FrequencyResponseStudy& study, const std::vector<FrequencyResponseRow>& rows);

void write_max_gain(const std::filesystem::path& dir, const StudyDocument& file, const MaxGainStudy& study,
                    const std::vector<MaxGainRow>& rows);

// Runs whichever study the file holds and writes it into dir (created if missing). False
// when an `rpsd_test` run aborted (its files are still complete for every step it took);
// `abort_reason` (optional) then receives why.
bool run_and_write(const StudyDocument& file, const std::filesystem::path& dir,
                   const std::function<void(std::int64_t, std::int64_t)>& progress = {},
                   std::string* abort_reason = nullptr);

}  // namespace rpsd::studies
