// Polynomial extrapolation (Horiuchi et al., EESD 28:1121, 1999): the command is the value,
// alpha = delay / dt steps ahead, of the Lagrange polynomial of order p through the last
// p + 1 targets: u[n] = sum_{j=0..p} c_j x_t[n - j], c_j = prod_{k != j} (alpha + k) / (k - j).
// For a smooth target its error is x^(p+1)(xi) / (p+1)! * prod_{k=0..p} (alpha + k) dt^(p+1).
#pragma once

#include <string_view>

#include "rpsd/config/source.h"

#include <array>
#include <complex>

#include "rpsd/compensation/command_compensator.h"

namespace rpsd::compensation {

inline constexpr int kMaxExtrapolationOrder = 3;

// c_0..c_order for order 0..3 and alpha >= 0 (unused entries are zero). Real-time safe;
// the order must be in range (checked by the caller's validation).
std::array<double, kMaxExtrapolationOrder + 1> extrapolation_coefficients(int order, double alpha);

// The extrapolator's frequency response at w dt = omega_dt_rad: sum_j c_j e^{-j j w dt}
// (the ideal is e^{j alpha w dt}). Real-time safe.
std::complex<double> extrapolation_response(int order, double alpha, double omega_dt_rad);

class PolynomialExtrapolationCompensator;

struct PolynomialExtrapolationParameters {
  static constexpr std::string_view kName = "polynomial_extrapolation";
  static constexpr std::string_view kSummary =
      "extrapolates the target tau ahead with a polynomial through its last p + 1 samples";
  using Compensator = PolynomialExtrapolationCompensator;
  static PolynomialExtrapolationParameters read(config::Source& section);

  int order = 2;         // p in 0..3 (0 holds the target: no compensation)
  double delay_s = 0.0;  // tau; alpha = tau / dt may be any non-negative ratio

  // Throws std::invalid_argument unless 0 <= order <= 3 and delay_s >= 0. Not real-time safe.
  void validate() const;
};

class PolynomialExtrapolationCompensator final : public CommandCompensator {
 public:
  explicit PolynomialExtrapolationCompensator(const PolynomialExtrapolationParameters& parameters);

  void configure(double dt_s) override;
  void reset(double initial_displacement_m) noexcept override;
  double command(double target_m) noexcept override;
  void observe(double, double) noexcept override {}
  // delay_s, or 0 for order 0 (which holds the target and so advances nothing).
  double compensated_delay_s() const noexcept override { return parameters_.order == 0 ? 0.0 : parameters_.delay_s; }
  std::string_view name() const noexcept override { return PolynomialExtrapolationParameters::kName; }

  double alpha() const { return alpha_; }
  const std::array<double, kMaxExtrapolationOrder + 1>& coefficients() const { return coefficients_; }

 private:
  PolynomialExtrapolationParameters parameters_;
  double alpha_ = 0.0;
  std::array<double, kMaxExtrapolationOrder + 1> coefficients_{};
  std::array<double, kMaxExtrapolationOrder + 1> history_m_{};  // x_t[n], x_t[n-1], ...
};

}  // namespace rpsd::compensation
