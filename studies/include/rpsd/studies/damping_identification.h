// Effective damping of a free-decay (or free-growth) response about zero: the peaks of |x|
// (one per half cycle) refined by parabolic interpolation, ln(peak) fitted by least squares against time. zeta = sigma
// / sqrt(sigma^2 + omega_d^2) with the decay rate sigma from the slope and omega_d from the peak spacing. Negative zeta
// means the response grows. Not real-time safe.
#pragma once

#include <span>

namespace rpsd::studies {

struct IdentifiedDamping {
  double damping_ratio = 0.0;
  double damped_frequency_hz = 0.0;
  int peaks_used = 0;
};

// Uses the peaks of |x| after skip_s seconds (to let a start-up transient pass) while
// they stay above floor_fraction of the first used one. Throws std::invalid_argument when
// fewer than three peaks remain.
IdentifiedDamping identify_damping(std::span<const double> response, double dt_s, double skip_s = 0.0,
                                   double floor_fraction = 1e-3);

}  // namespace rpsd::studies
