#include "rpsd/hybrid_test/monte_carlo.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace rpsd::hybrid_test {

std::vector<std::vector<double>> draw_monte_carlo(const MonteCarloConfig& config) {
  std::mt19937_64 generator(config.seed);
  std::vector<std::vector<double>> values;
  for (int run = 0; run < config.runs; ++run) {
    std::vector<double>& v = values.emplace_back();
    for (const MonteCarloParameter& p : config.parameters) {
      // A fresh distribution per draw: no cached second normal carries from one run to the next.
      if (p.distribution == MonteCarloParameter::Distribution::kNormal) {
        v.push_back(p.nominal + p.spread * std::normal_distribution<double>(0.0, 1.0)(generator));
      } else {
        v.push_back(p.nominal + p.spread * std::uniform_real_distribution<double>(-1.0, 1.0)(generator));
      }
    }
  }
  return values;
}

RunStatistics run_statistics(std::span<const double> values) {
  RunStatistics s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  s.minimum = std::numeric_limits<double>::infinity();
  s.maximum = -s.minimum;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++s.runs;
    sum += v;
    s.minimum = std::min(s.minimum, v);
    s.maximum = std::max(s.maximum, v);
  }
  if (s.runs == 0) return {0, nan, nan, nan, nan};
  s.mean = sum / s.runs;
  double squares = 0.0;  // two passes: no cancellation for values far from zero
  for (double v : values) {
    if (std::isfinite(v)) squares += (v - s.mean) * (v - s.mean);
  }
  s.standard_deviation = s.runs > 1 ? std::sqrt(squares / (s.runs - 1)) : nan;
  return s;
}

}  // namespace rpsd::hybrid_test
