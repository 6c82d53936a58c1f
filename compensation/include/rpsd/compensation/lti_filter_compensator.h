// Any linear compensator given as a continuous transfer function N(s)/D(s), run at the
// control rate as its Tustin image (tustin.h), optionally pre-warped: the general lead/lag
// network of the RTHS benchmark's sample controller, G_T = 50.8 (s + 168.6) / (s + 8570),
// as published, or any filter of higher order.
#pragma once

#include <string_view>
#include <vector>

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/tustin.h"
#include "rpsd/config/source.h"

namespace rpsd::compensation {

class LtiFilterCompensator;

struct LtiFilterParameters {
  static constexpr std::string_view kName = "lti_filter";
  static constexpr std::string_view kSummary =
      "a linear filter N(s)/D(s) from its coefficients, Tustin at the control rate (optionally pre-warped)";
  using Compensator = LtiFilterCompensator;
  static LtiFilterParameters read(config::Source& section);

  ContinuousTransferFunction transfer_function;
  double prewarp_frequency_hz = 0.0;  // 0: plain Tustin; > 0: exact at this frequency
  // The target as the filter receives it: clamped to +/- input_saturation_m, then rounded to
  // the nearest multiple of input_step_m (0: neither), as the RTHS benchmark's released model
  // quantises y_n (2^-18, +/-3.8) before G_T. A non-finite target passes unchanged.
  double input_step_m = 0.0;
  double input_saturation_m = 0.0;

  // Throws std::invalid_argument unless the transfer function is proper, its poles lie in
  // the open left half-plane (a stable filter with a finite DC gain) and the pre-warping
  // frequency is below the Nyquist frequency of dt_s. Not real-time safe.
  void validate(double dt_s) const;
};

class LtiFilterCompensator final : public CommandCompensator {
 public:
  explicit LtiFilterCompensator(const LtiFilterParameters& parameters);

  void configure(double dt_s) override;
  // At rest: the input holds initial_displacement_m and the output is its DC image G(0) x0.
  void reset(double initial_displacement_m) noexcept override;
  double command(double target_m) noexcept override;
  void observe(double, double) noexcept override {}
  // The low-frequency lead d(arg G)/dw at 0 of the discrete filter: (N1/N0 - D1/D0) K dt / 2.
  double compensated_delay_s() const noexcept override { return low_frequency_lead_s_; }
  std::string_view name() const noexcept override { return LtiFilterParameters::kName; }

  const DiscreteFilterCoefficients& coefficients() const { return coefficients_; }

 private:
  double quantised_input(double target_m) const noexcept;

  LtiFilterParameters parameters_;
  DiscreteFilterCoefficients coefficients_;
  std::vector<double> state_;  // direct form II transposed
  double low_frequency_lead_s_ = 0.0;
};

}  // namespace rpsd::compensation
