// Plant uncertainty as the RTHS benchmark asks for it: N runs, each with the named parameters
// drawn about their nominal values from one seeded generator (std::mt19937_64, run by run,
// parameter by parameter, so a run's values depend only on the seed and its number), and the
// statistics of every criterion over the runs. Not real-time safe.
#pragma once

#include <span>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_document.h"

namespace rpsd::hybrid_test {

// values[run][parameter]. Normal: nominal + spread N(0, 1); uniform: nominal + spread U(-1, 1).
std::vector<std::vector<double>> draw_monte_carlo(const MonteCarloConfig& config);

struct RunStatistics {
  int runs = 0;                     // finite values counted (the batch passes only completed runs')
  double mean = 0.0;                // NaN when none
  double standard_deviation = 0.0;  // sample (n - 1); NaN below two
  double minimum = 0.0;
  double maximum = 0.0;
};

// Over the finite values (NaN ones, e.g. a J1 that could not be found, are left out).
RunStatistics run_statistics(std::span<const double> values);

}  // namespace rpsd::hybrid_test
