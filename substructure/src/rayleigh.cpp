#include "rpsd/substructure/rayleigh.h"

#include "matrix_checks.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::substructure {

double rayleigh_damping_ratio(const RayleighCoefficients& c, double omega_rad_s) noexcept {
  return c.a0_per_s / (2.0 * omega_rad_s) + c.a1_s * omega_rad_s / 2.0;
}

RayleighCoefficients rayleigh_from_frequencies(double wa, double wb, double za, double zb) {
  using detail::fmt;
  const std::string ctx = "Rayleigh damping: ";
  if (!(std::isfinite(wa) && wa > 0.0) || !(std::isfinite(wb) && wb > 0.0)) {
    throw std::invalid_argument(ctx + "the two circular frequencies must be positive and finite, got " + fmt(wa) +
                                " and " + fmt(wb) + " rad/s");
  }
  if (std::abs(wb - wa) <= 1e-12 * std::max(wa, wb)) {
    throw std::invalid_argument(ctx + "the two frequencies are equal (" + fmt(wa) +
                                " rad/s); choose two modes with distinct frequencies");
  }
  if (!(std::isfinite(za) && za >= 0.0) || !(std::isfinite(zb) && zb >= 0.0)) {
    throw std::invalid_argument(ctx + "damping ratios must be non-negative and finite, got " + fmt(za) + " and " +
                                fmt(zb));
  }
  const double den = wb * wb - wa * wa;
  RayleighCoefficients c;
  c.a0_per_s = 2.0 * wa * wb * (za * wb - zb * wa) / den;
  c.a1_s = 2.0 * (zb * wb - za * wa) / den;
  // Round-off can leave -1e-20 where the exact value is 0 (e.g. ζ ∝ ω): clamp that only.
  const double tol = 1e-12;
  if (c.a0_per_s < -tol * (std::abs(c.a1_s) * wa * wb + 1e-300) ||
      c.a1_s < -tol * (std::abs(c.a0_per_s) / (wa * wb) + 1e-300)) {
    throw std::invalid_argument(ctx + "ratios " + fmt(za) + " at " + fmt(wa) + " rad/s and " + fmt(zb) + " at " +
                                fmt(wb) + " rad/s need a negative coefficient (a0 = " + fmt(c.a0_per_s) +
                                " 1/s, a1 = " + fmt(c.a1_s) + " s), which gives negative damping at some frequencies");
  }
  c.a0_per_s = std::max(c.a0_per_s, 0.0);
  c.a1_s = std::max(c.a1_s, 0.0);
  return c;
}

}  // namespace rpsd::substructure
