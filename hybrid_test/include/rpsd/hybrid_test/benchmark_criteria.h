// The RTHS benchmark's nine criteria (Silva et al. 2020) in the paper's order and with the
// paper's definitions: J1-J3 on channel 0, J4-J6 RMS and J7-J9 peak errors of the first three
// recorded floors against the perfect-actuator reference, an experimental floor taken from its
// measured x_m. Each has its number and a name that says what it measures, for summary.json,
// the Monte Carlo table and the benchmark study (docs/benchmark.md).
#pragma once

#include <array>
#include <string_view>

#include <nlohmann/json.hpp>

#include "rpsd/coordinator/run_criteria.h"

namespace rpsd::hybrid_test {

struct BenchmarkCriterion {
  std::string_view number;    // "J4"
  std::string_view name;      // "J4_rms_error_floor_1_percent"
  std::string_view measures;  // one sentence
};

inline constexpr std::size_t kBenchmarkCriteria = 9;
extern const std::array<BenchmarkCriterion, kBenchmarkCriteria> kBenchmarkCriterionList;

// J1..J9 of a run; NaN where the test has no such channel or floor (or J1 could not be found).
std::array<double, kBenchmarkCriteria> benchmark_values(const coordinator::Criteria& criteria);

// {"J1": value, ...} with null for NaN; the criteria a test has.
nlohmann::json benchmark_criteria_json(const coordinator::Criteria& criteria);
// {"J1": {"name": ..., "measures": ...}, ...} for the same criteria.
nlohmann::json benchmark_criteria_definitions(const coordinator::Criteria& criteria);

}  // namespace rpsd::hybrid_test
