#include "rpsd/studies/damping_identification.h"

#include "rpsd/studies/line_fit.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace rpsd::studies {

IdentifiedDamping identify_damping(std::span<const double> x, double dt_s, double skip_s, double floor_fraction) {
  std::vector<double> times, logs;
  const auto first = static_cast<std::size_t>(std::ceil(skip_s / dt_s)) + 1;
  double first_peak = 0.0;
  for (std::size_t i = std::max<std::size_t>(first, 1); i + 1 < x.size(); ++i) {
    // Peaks of |x|: one every half cycle, so that a fast-growing response still gives several.
    const double a = std::abs(x[i - 1]), b = std::abs(x[i]), c = std::abs(x[i + 1]);
    if (!(b > 0.0 && b >= a && b > c)) continue;
    // Parabola through the three samples around the peak.
    const double denominator = a - 2.0 * b + c;
    const double offset = denominator != 0.0 ? 0.5 * (a - c) / denominator : 0.0;
    const double peak = b - 0.25 * (a - c) * offset;
    if (times.empty()) first_peak = peak;
    if (peak < floor_fraction * first_peak) break;
    times.push_back((static_cast<double>(i) + offset) * dt_s);
    logs.push_back(std::log(peak));
  }
  if (times.size() < 3) throw std::invalid_argument("identify_damping: fewer than three peaks to fit");
  const double n = static_cast<double>(times.size());
  const double slope = least_squares_slope(times, logs);  // = -sigma
  const double period = 2.0 * (times.back() - times.front()) / (n - 1.0);
  const double omega_d = 2.0 * std::numbers::pi / period;
  const double sigma = -slope;
  return {sigma / std::hypot(sigma, omega_d), 1.0 / period, static_cast<int>(times.size())};
}

}  // namespace rpsd::studies
