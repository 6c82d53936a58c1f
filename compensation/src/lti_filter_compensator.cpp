#include "rpsd/compensation/lti_filter_compensator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "validation.h"

namespace rpsd::compensation {

void LtiFilterParameters::validate(double dt_s) const {
  detail::require_positive("lti filter: dt_s", dt_s);
  detail::require_non_negative("lti filter: prewarp_frequency_hz", prewarp_frequency_hz);
  detail::require_non_negative("lti filter: input_step_m", input_step_m);
  detail::require_non_negative("lti filter: input_saturation_m", input_saturation_m);
  (void)tustin(transfer_function, dt_s, prewarp_frequency_hz);  // proper, finite, below Nyquist
  for (const auto& pole : polynomial_roots(transfer_function.denominator)) {
    if (!(pole.real() < 0.0)) {
      throw std::invalid_argument("lti filter: a pole at s = " + std::to_string(pole.real()) + " + " +
                                  std::to_string(pole.imag()) +
                                  "j is not in the left half-plane: a compensator must be stable, with a finite "
                                  "DC gain");
    }
  }
}

LtiFilterCompensator::LtiFilterCompensator(const LtiFilterParameters& parameters) : parameters_(parameters) {}

void LtiFilterCompensator::configure(double dt_s) {
  parameters_.validate(dt_s);
  coefficients_ = tustin(parameters_.transfer_function, dt_s, parameters_.prewarp_frequency_hz);
  state_.assign(coefficients_.a.size() - 1, 0.0);
  // d(arg G(jw))/dw at 0 = N1/N0 - D1/D0 (ascending coefficients); the map scales it by K dt / 2.
  const auto& n = parameters_.transfer_function.numerator;
  const auto& d = parameters_.transfer_function.denominator;
  const auto ascending = [](const std::vector<double>& c, std::size_t k) {
    return k < c.size() ? c[c.size() - 1 - k] : 0.0;
  };
  const double n0 = ascending(n, 0), d0 = ascending(d, 0);
  low_frequency_lead_s_ = n0 == 0.0 ? 0.0
                                    : (ascending(n, 1) / n0 - ascending(d, 1) / d0) *
                                          tustin_constant(dt_s, parameters_.prewarp_frequency_hz) * dt_s / 2.0;
  reset(0.0);
}

double LtiFilterCompensator::quantised_input(double target_m) const noexcept {
  if (!std::isfinite(target_m)) return target_m;
  const double limit = parameters_.input_saturation_m, step = parameters_.input_step_m;
  double x = limit > 0.0 ? std::clamp(target_m, -limit, limit) : target_m;
  if (step > 0.0) x = step * std::round(x / step);  // halves away from zero, as the converters
  return x;
}

void LtiFilterCompensator::reset(double initial_displacement_m) noexcept {
  // The steady state of a constant input x: y = G(0) x, s_i = sum_{k >= i} (b_k x - a_k y).
  const auto& b = coefficients_.b;
  const auto& a = coefficients_.a;
  double b_sum = 0.0, a_sum = 0.0;
  for (double v : b) b_sum += v;
  for (double v : a) a_sum += v;
  const double x = quantised_input(initial_displacement_m), y = b_sum / a_sum * x;
  double tail = 0.0;
  for (std::size_t i = state_.size(); i >= 1; --i) {
    tail += b[i] * x - a[i] * y;
    state_[i - 1] = tail;
  }
}

double LtiFilterCompensator::command(double target) noexcept {
  const double target_m = quantised_input(target);
  const auto& b = coefficients_.b;
  const auto& a = coefficients_.a;
  const std::size_t n = state_.size();
  const double y = b[0] * target_m + (n > 0 ? state_[0] : 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) state_[i] = state_[i + 1] + b[i + 1] * target_m - a[i + 1] * y;
  if (n > 0) state_[n - 1] = b[n] * target_m - a[n] * y;
  return y;
}

LtiFilterParameters LtiFilterParameters::read(config::Source& section) {
  LtiFilterParameters p;
  const config::Number coefficient = config::Number::between(-1e15, 1e15, "", "a coefficient, descending powers of s");
  p.transfer_function.numerator = section.numbers("numerator", coefficient, 16);
  p.transfer_function.denominator = section.numbers("denominator", coefficient, 16);
  p.prewarp_frequency_hz =
      section.number_or("prewarp_frequency_hz", 0.0,
                        config::Number::between(0.0, 1e4, "Hz", "Tustin exact at this frequency (0: plain Tustin)"));
  p.input_step_m = section.number_or(
      "input_step_m", 0.0, config::Number::between(0.0, 1.0, "m", "the target rounded to this step first (0: none)"));
  p.input_saturation_m =
      section.number_or("input_saturation_m", 0.0,
                        config::Number::between(0.0, 1e3, "m", "the target clamped to +/- this first (0: none)"));
  return p;
}

}  // namespace rpsd::compensation
