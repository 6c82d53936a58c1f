// What an operator did to a run, for its output folder: summary.json's operator_commands
// (every command heard, accepted or refused, with who and when), held (each interval an
// operator held a lock-step test) and return_to_start, and return_to_start.csv.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "rpsd/hybrid_test/hybrid_test_assembly.h"

namespace rpsd::hybrid_test {

nlohmann::json operator_commands_json(const TestRun& test);
nlohmann::json held_intervals_json(const TestRun& test);
// null when the run did not return to its start positions.
nlohmann::json return_to_start_json(const TestRun& test);
// return_to_start.csv, when the run returned: time_s and per channel target_<c>,
// command_m_<c>, measured_m_<c>, force_n_<c>, one row per exchange of the ramp.
void write_return_to_start(const std::filesystem::path& dir, const TestRun& test);
// "operator stop by \"alice@rig\"" and the like, for the outcome's text.
std::string operator_outcome_detail(const TestRun& test);

}  // namespace rpsd::hybrid_test
