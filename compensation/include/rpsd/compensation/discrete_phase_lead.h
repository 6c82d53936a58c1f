// The phase-lead network G_c(s) = (1 + a T s) / (1 + T s) run at the control rate, discretised by
// Tustin, s = K (z - 1) / (z + 1) with K = 2 / dt (or pre-warped at prewarp_frequency_hz), because
// the bilinear map keeps the DC gain 1, the gain at most a, the filter stable for every T >= 0 and,
// without pre-warping, the low-frequency lead (a - 1) T exactly.
// Derivation and the alternatives considered: docs/compensation.md
#pragma once

#include <string_view>

#include "rpsd/config/source.h"

#include <complex>

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/phase_lead.h"

namespace rpsd::compensation {

class DiscretePhaseLeadCompensator;

struct DiscretePhaseLeadParameters {
  static constexpr std::string_view kName = "phase_lead";
  static constexpr std::string_view kSummary =
      "the seed paper's first-order phase-lead network (1 + a T s) / (1 + T s), Tustin at the control rate";
  using Compensator = DiscretePhaseLeadCompensator;
  static DiscretePhaseLeadParameters read(config::Source& section);

  PhaseLeadParameters network;        // (a, T); see phase_lead_for_delay() for the design
  double prewarp_frequency_hz = 0.0;  // 0: plain Tustin; > 0: exact at this frequency

  // Designed from the delay to compensate with the chosen ratio a: (a - 1) T = delay_s.
  static DiscretePhaseLeadParameters for_delay(double delay_s, double ratio_a, double prewarp_frequency_hz = 0.0);

  // Throws std::invalid_argument unless the network is valid and 0 <= prewarp < Nyquist
  // of dt_s. Not real-time safe.
  void validate(double dt_s) const;
};

// One first-order section y[n] = b0 x[n] + b1 x[n-1] - a1 y[n-1].
struct FirstOrderSection {
  double b0 = 1.0;
  double b1 = 0.0;
  double a1 = 0.0;
};

// The Tustin coefficients of the network at step dt_s (validates). Not real-time safe.
FirstOrderSection tustin_phase_lead(const DiscretePhaseLeadParameters& parameters, double dt_s);

// The bilinear frequency-warping constant K (2 / dt_s, or pre-warped). Real-time safe.
double tustin_warping_constant(const DiscretePhaseLeadParameters& parameters, double dt_s);

// The discrete network's exact frequency response at w = omega_rad_s:
// G_c(j K tan(w dt / 2)) (the bilinear map), for 0 <= w dt < pi. Real-time safe.
std::complex<double> discrete_phase_lead_response(const DiscretePhaseLeadParameters& parameters, double dt_s,
                                                  double omega_rad_s);

class DiscretePhaseLeadCompensator final : public CommandCompensator {
 public:
  explicit DiscretePhaseLeadCompensator(const DiscretePhaseLeadParameters& parameters);

  void configure(double dt_s) override;
  void reset(double initial_displacement_m) noexcept override;
  // Inline: the exchange calls it directly on every step (compensator_call.h).
  double command(double target_m) noexcept override {
    const double y = section_.b0 * target_m + section_.b1 * previous_input_m_ - section_.a1 * previous_output_m_;
    previous_input_m_ = target_m;
    previous_output_m_ = y;
    return y;
  }
  void observe(double, double) noexcept override {}
  // The discrete filter's low-frequency lead: (a - 1) T K dt / 2 ((a - 1) T unless pre-warped).
  double compensated_delay_s() const noexcept override { return low_frequency_lead_s_; }
  std::string_view name() const noexcept override { return DiscretePhaseLeadParameters::kName; }

  const FirstOrderSection& section() const { return section_; }
  const DiscretePhaseLeadParameters& parameters() const { return parameters_; }

 private:
  DiscretePhaseLeadParameters parameters_;
  FirstOrderSection section_;
  double low_frequency_lead_s_ = 0.0;
  double previous_input_m_ = 0.0;
  double previous_output_m_ = 0.0;
};

}  // namespace rpsd::compensation
