#include "rpsd/hybrid_test/benchmark_criteria.h"

#include <cmath>
#include <string>

namespace rpsd::hybrid_test {

const std::array<BenchmarkCriterion, kBenchmarkCriteria> kBenchmarkCriterionList = {{
    {"J1", "J1_tracking_delay_ms",
     "lag of the measured displacement x_m behind its target y_n (channel 0): the whole-sample lag in 0..49 "
     "samples maximising their cross-correlation, ms (the benchmark's; rpsd's signed tracking_delay_ms is per "
     "channel)"},
    {"J2", "J2_rms_tracking_error_percent", "RMS of x_m - y_n over the RMS of y_n (channel 0), %"},
    {"J3", "J3_peak_tracking_error_percent", "peak of |x_m - y_n| over the peak of |y_n| (channel 0), %"},
    {"J4", "J4_rms_error_floor_1_percent",
     "RMS error of floor 1 (x_m where it is experimental) against the perfect-actuator reference, over the "
     "reference's RMS, %"},
    {"J5", "J5_rms_error_floor_2_percent", "the same for floor 2, %"},
    {"J6", "J6_rms_error_floor_3_percent", "the same for floor 3, %"},
    {"J7", "J7_peak_error_floor_1_percent",
     "peak error of floor 1 (x_m where it is experimental) against the reference, over the reference's peak, %"},
    {"J8", "J8_peak_error_floor_2_percent", "the same for floor 2, %"},
    {"J9", "J9_peak_error_floor_3_percent", "the same for floor 3, %"},
}};

std::array<double, kBenchmarkCriteria> benchmark_values(const coordinator::Criteria& criteria) {
  std::array<double, kBenchmarkCriteria> j;
  j.fill(std::nan(""));
  if (!criteria.channels.empty()) {
    j[0] = criteria.channels[0].j1_tracking_delay_ms;
    j[1] = criteria.channels[0].j2_rms_tracking_error_percent;
    j[2] = criteria.channels[0].j3_peak_tracking_error_percent;
  }
  for (std::size_t d = 0; d < 3 && d < criteria.dofs.size(); ++d) {
    j[3 + d] = criteria.dofs[d].rms_error_percent;
    j[6 + d] = criteria.dofs[d].peak_error_percent;
  }
  return j;
}

namespace {
// The criteria a test has: J1-J3 with a channel, J(4+d) and J(7+d) with floor d.
bool has(const coordinator::Criteria& criteria, std::size_t i) {
  if (i < 3) return !criteria.channels.empty();
  return (i - 3) % 3 < criteria.dofs.size();
}
}  // namespace

nlohmann::json benchmark_criteria_json(const coordinator::Criteria& criteria) {
  const auto values = benchmark_values(criteria);
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < kBenchmarkCriteria; ++i) {
    if (!has(criteria, i)) continue;
    out[std::string(kBenchmarkCriterionList[i].number)] =
        std::isfinite(values[i]) ? nlohmann::json(values[i]) : nlohmann::json(nullptr);
  }
  return out;
}

nlohmann::json benchmark_criteria_definitions(const coordinator::Criteria& criteria) {
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < kBenchmarkCriteria; ++i) {
    if (!has(criteria, i)) continue;
    const auto& c = kBenchmarkCriterionList[i];
    out[std::string(c.number)] = {{"name", c.name}, {"measures", c.measures}};
  }
  return out;
}

}  // namespace rpsd::hybrid_test
