// The benchmark's numbering is the paper's (Silva et al. 2020): J4-J6 the RMS errors of floors
// 1-3, J7-J9 their peak errors; the benchmark's evaluation script orders them RMS floor 1,
// peak floor 1, RMS floors 2-3, peak floors 2-3, which must not be what rpsd writes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rpsd/hybrid_test/benchmark_criteria.h"

namespace rpsd::hybrid_test {
namespace {

coordinator::Criteria distinct_criteria(std::size_t floors) {
  coordinator::Criteria c;
  c.channels.push_back({11.0, 12.0, 13.0, 0.0});
  for (std::size_t d = 0; d < floors; ++d) {
    coordinator::DofCriteria dof;
    dof.rms_error_percent = 40.0 + static_cast<double>(d);   // floor d + 1's RMS error
    dof.peak_error_percent = 70.0 + static_cast<double>(d);  // its peak error
    c.dofs.push_back(dof);
  }
  return c;
}

TEST(BenchmarkCriteria, NumbersFollowThePaperRmsOfFloorsOneToThreeThenTheirPeaks) {
  const auto j = benchmark_values(distinct_criteria(3));
  const double expected[] = {11.0, 12.0, 13.0, 40.0, 41.0, 42.0, 70.0, 71.0, 72.0};
  for (std::size_t i = 0; i < kBenchmarkCriteria; ++i) EXPECT_EQ(j[i], expected[i]) << "J" << i + 1;
  const nlohmann::json json = benchmark_criteria_json(distinct_criteria(3));
  EXPECT_EQ(json["J5"].get<double>(), 41.0);
  EXPECT_EQ(json["J7"].get<double>(), 70.0);
}

TEST(BenchmarkCriteria, EachNameSaysWhatItMeasuresAndAMissingFloorIsLeftOut) {
  const nlohmann::json definitions = benchmark_criteria_definitions(distinct_criteria(1));
  EXPECT_EQ(definitions.size(), 5u);  // J1-J3, J4 and J7
  EXPECT_EQ(definitions["J4"]["name"], "J4_rms_error_floor_1_percent");
  EXPECT_EQ(definitions["J7"]["name"], "J7_peak_error_floor_1_percent");
  EXPECT_NE(definitions["J4"]["measures"].get<std::string>().find("x_m"), std::string::npos);
  EXPECT_FALSE(definitions.contains("J5"));
  coordinator::Criteria no_delay = distinct_criteria(1);
  no_delay.channels[0].j1_tracking_delay_ms = std::nan("");
  EXPECT_TRUE(benchmark_criteria_json(no_delay)["J1"].is_null());
  EXPECT_TRUE(std::isnan(benchmark_values(no_delay)[4]));
}

}  // namespace
}  // namespace rpsd::hybrid_test
