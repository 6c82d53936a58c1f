// Monte Carlo draws and statistics against their definitions: the draws against a generator
// seeded the same way by hand and against the distributions' moments, the statistics against
// values worked out on paper.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "rpsd/hybrid_test/monte_carlo.h"

namespace rpsd::hybrid_test {
namespace {

using Distribution = MonteCarloParameter::Distribution;

MonteCarloConfig benchmark_like(int runs, std::uint64_t seed) {
  MonteCarloConfig c;
  c.runs = runs;
  c.seed = seed;
  c.parameters = {{"servo.a3_per_s", Distribution::kNormal, 3.3, 1.3, {}},
                  {"servo.k", Distribution::kUniform, 1.19e6, 5e4, {}}};
  return c;
}

TEST(MonteCarlo, DrawsAreTheSeededGeneratorsRunByRunParameterByParameter) {
  const auto draws = draw_monte_carlo(benchmark_like(3, 2021));
  std::mt19937_64 generator(2021);
  ASSERT_EQ(draws.size(), 3u);
  for (const auto& run : draws) {
    ASSERT_EQ(run.size(), 2u);
    EXPECT_EQ(run[0], 3.3 + 1.3 * std::normal_distribution<double>(0.0, 1.0)(generator));
    EXPECT_EQ(run[1], 1.19e6 + 5e4 * std::uniform_real_distribution<double>(-1.0, 1.0)(generator));
  }
  // A run's values depend on the seed and its number only, not on how many runs follow.
  const auto more = draw_monte_carlo(benchmark_like(10, 2021));
  for (std::size_t r = 0; r < 3; ++r) EXPECT_EQ(more[r], draws[r]);
  EXPECT_NE(draw_monte_carlo(benchmark_like(3, 2022))[0], draws[0]);
}

TEST(MonteCarlo, DrawsHaveTheirDistributionsMoments) {
  // 20000 runs: the normal's mean within 4 standard errors and its standard deviation within
  // 3 %; the uniform's inside +/- its half width with standard deviation h / sqrt 3.
  const auto draws = draw_monte_carlo(benchmark_like(20000, 7));
  std::vector<double> normal, uniform;
  for (const auto& run : draws) {
    normal.push_back(run[0]);
    uniform.push_back(run[1]);
    ASSERT_LE(std::abs(run[1] - 1.19e6), 5e4);
  }
  const RunStatistics n = run_statistics(normal), u = run_statistics(uniform);
  EXPECT_NEAR(n.mean, 3.3, 4.0 * 1.3 / std::sqrt(20000.0));
  EXPECT_NEAR(n.standard_deviation / 1.3, 1.0, 0.03);
  EXPECT_NEAR(u.mean, 1.19e6, 4.0 * 5e4 / std::sqrt(3.0 * 20000.0));
  EXPECT_NEAR(u.standard_deviation / (5e4 / std::sqrt(3.0)), 1.0, 0.03);
}

TEST(MonteCarlo, StatisticsAreTheSampleMeanDeviationAndExtremesOfTheFiniteValues) {
  // {1, 2, 3, 4, 10}: mean 4, squares 9 + 4 + 1 + 0 + 36 = 50, sample variance 50 / 4.
  const std::vector<double> values{1.0, std::nan(""), 2.0, 3.0, 4.0, 10.0};
  const RunStatistics s = run_statistics(values);
  EXPECT_EQ(s.runs, 5);
  EXPECT_DOUBLE_EQ(s.mean, 4.0);
  EXPECT_DOUBLE_EQ(s.standard_deviation, std::sqrt(12.5));
  EXPECT_EQ(s.minimum, 1.0);
  EXPECT_EQ(s.maximum, 10.0);
  // Far from zero, two passes keep the deviation exact where one pass would cancel.
  const RunStatistics far = run_statistics(std::vector<double>{1e9 + 1.0, 1e9 + 2.0, 1e9 + 3.0});
  EXPECT_DOUBLE_EQ(far.standard_deviation, 1.0);
  const RunStatistics one = run_statistics(std::vector<double>{5.0});
  EXPECT_EQ(one.mean, 5.0);
  EXPECT_TRUE(std::isnan(one.standard_deviation));
  EXPECT_TRUE(std::isnan(run_statistics(std::vector<double>{std::nan("")}).mean));
}

}  // namespace
}  // namespace rpsd::hybrid_test
