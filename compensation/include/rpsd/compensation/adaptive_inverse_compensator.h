// Adaptive inverse compensation (after Chen & Ricles, J. Struct. Eng. 2010): the inverse compensator
// (inverse_compensator.h) whose delay tau = (alpha - 1) dt follows the tracking indicator TI
// (tracking_indicator.h) of target against measured displacement, tau -> tau_0 + k_p TI + k_i integral TI dt,
// within [tau_min, tau_max] and at most r per second, so that the compensation follows a changing lag.
// Derivation and sources: docs/compensation.md
#pragma once

#include <string_view>

#include "rpsd/config/source.h"

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/tracking_indicator.h"

namespace rpsd::compensation {

class AdaptiveInverseCompensator;

struct AdaptiveInverseCompensationParameters {
  static constexpr std::string_view kName = "adaptive_inverse";
  static constexpr std::string_view kSummary =
      "inverse compensation whose delay adapts to the tracking indicator (Chen and Ricles)";
  using Compensator = AdaptiveInverseCompensator;
  static AdaptiveInverseCompensationParameters read(config::Source& section);

  double initial_delay_s = 0.0;             // tau_0
  double min_delay_s = 0.0;                 // tau_min >= 0
  double max_delay_s = 0.1;                 // tau_max >= tau_min
  double max_delay_rate = 0.05;             // r: seconds of delay per second, > 0
  double proportional_gain_s_per_m2 = 0.0;  // k_p >= 0
  double integral_gain_per_m2 = 0.0;        // k_i >= 0 (s of delay per m^2 s)

  // Throws std::invalid_argument with the offending value unless 0 <= tau_min <= tau_0 <=
  // tau_max, r > 0 and the gains are >= 0. Not real-time safe.
  void validate() const;
};

class AdaptiveInverseCompensator final : public CommandCompensator {
 public:
  explicit AdaptiveInverseCompensator(const AdaptiveInverseCompensationParameters& parameters);

  void configure(double dt_s) override;
  void reset(double initial_displacement_m) noexcept override;
  double command(double target_m) noexcept override;
  void observe(double target_m, double measured_m) noexcept override;
  double compensated_delay_s() const noexcept override { return delay_s_; }
  std::string_view name() const noexcept override { return AdaptiveInverseCompensationParameters::kName; }

  double alpha() const { return 1.0 + delay_s_ / dt_s_; }
  const TrackingIndicator& tracking_indicator() const { return indicator_; }

 private:
  AdaptiveInverseCompensationParameters parameters_;
  double dt_s_ = 1.0;
  double delay_s_ = 0.0;
  double ti_integral_m2_s_ = 0.0;
  double previous_target_m_ = 0.0;
  TrackingIndicator indicator_;
};

}  // namespace rpsd::compensation
