#include "rpsd/compensation/polynomial_extrapolation.h"

#include <string>

#include "validation.h"

namespace rpsd::compensation {

std::array<double, kMaxExtrapolationOrder + 1> extrapolation_coefficients(int order, double alpha) {
  std::array<double, kMaxExtrapolationOrder + 1> c{};
  for (int j = 0; j <= order; ++j) {
    double product = 1.0;
    for (int k = 0; k <= order; ++k) {
      if (k != j) product *= (alpha + k) / static_cast<double>(k - j);
    }
    c[static_cast<std::size_t>(j)] = product;
  }
  return c;
}

std::complex<double> extrapolation_response(int order, double alpha, double omega_dt_rad) {
  const auto c = extrapolation_coefficients(order, alpha);
  std::complex<double> h = 0.0;
  for (int j = 0; j <= order; ++j) h += c[static_cast<std::size_t>(j)] * std::polar(1.0, -j * omega_dt_rad);
  return h;
}

void PolynomialExtrapolationParameters::validate() const {
  if (order < 0 || order > kMaxExtrapolationOrder) {
    detail::fail("polynomial extrapolation: order", "must be 0, 1, 2 or 3", order);
  }
  detail::require_non_negative("polynomial extrapolation: delay_s", delay_s);
}

PolynomialExtrapolationCompensator::PolynomialExtrapolationCompensator(
    const PolynomialExtrapolationParameters& parameters)
    : parameters_(parameters) {
  parameters_.validate();
}

void PolynomialExtrapolationCompensator::configure(double dt_s) {
  detail::require_positive("polynomial extrapolation: dt_s", dt_s);
  alpha_ = parameters_.delay_s / dt_s;
  coefficients_ = extrapolation_coefficients(parameters_.order, alpha_);
  reset(0.0);
}

void PolynomialExtrapolationCompensator::reset(double initial_displacement_m) noexcept {
  history_m_.fill(initial_displacement_m);
}

double PolynomialExtrapolationCompensator::command(double target_m) noexcept {
  for (std::size_t j = history_m_.size() - 1; j > 0; --j) history_m_[j] = history_m_[j - 1];
  history_m_[0] = target_m;
  double u = 0.0;
  for (std::size_t j = 0; j < history_m_.size(); ++j) u += coefficients_[j] * history_m_[j];
  return u;
}

PolynomialExtrapolationParameters PolynomialExtrapolationParameters::read(config::Source& section) {
  PolynomialExtrapolationParameters p;
  p.order = static_cast<int>(
      section.whole_number("order", 0, kMaxExtrapolationOrder, "p: the polynomial's order (0 holds the target)"));
  p.delay_s = section.number("delay_s",
                             config::Number::between(0.0, 1.0, "s", "tau: how far ahead the target is extrapolated"));
  return p;
}

}  // namespace rpsd::compensation
