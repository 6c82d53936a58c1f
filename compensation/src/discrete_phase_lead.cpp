#include "rpsd/compensation/discrete_phase_lead.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "validation.h"

namespace rpsd::compensation {

DiscretePhaseLeadParameters DiscretePhaseLeadParameters::for_delay(double delay_s, double ratio_a,
                                                                   double prewarp_frequency_hz) {
  return DiscretePhaseLeadParameters{phase_lead_for_delay(delay_s, ratio_a), prewarp_frequency_hz};
}

void DiscretePhaseLeadParameters::validate(double dt_s) const {
  detail::require_positive("phase lead compensator: dt_s", dt_s);
  network.validate();
  detail::require_non_negative("phase lead compensator: prewarp_frequency_hz", prewarp_frequency_hz);
  const double nyquist_hz = 0.5 / dt_s;
  if (!(prewarp_frequency_hz < nyquist_hz)) {
    detail::fail("phase lead compensator: prewarp_frequency_hz",
                 "must be below the Nyquist frequency " + std::to_string(nyquist_hz) + " Hz of dt_s",
                 prewarp_frequency_hz);
  }
}

double tustin_warping_constant(const DiscretePhaseLeadParameters& parameters, double dt_s) {
  if (parameters.prewarp_frequency_hz == 0.0) return 2.0 / dt_s;
  const double omega_p = 2.0 * std::numbers::pi * parameters.prewarp_frequency_hz;
  return omega_p / std::tan(0.5 * omega_p * dt_s);
}

FirstOrderSection tustin_phase_lead(const DiscretePhaseLeadParameters& parameters, double dt_s) {
  parameters.validate(dt_s);
  const double a = parameters.network.ratio_a;
  const double T = parameters.network.time_constant_s;
  // T = 0 or a = 1 is the identity; written out so that the pole at z = -1 of the T = 0
  // bilinear image never appears.
  if (T == 0.0 || a == 1.0) return FirstOrderSection{1.0, 0.0, 0.0};
  const double K = tustin_warping_constant(parameters, dt_s);
  // (1 + a T s) / (1 + T s) with s = K (1 - z^-1) / (1 + z^-1), multiplied through by (1 + z^-1).
  const double den = 1.0 + T * K;
  return FirstOrderSection{(1.0 + a * T * K) / den, (1.0 - a * T * K) / den, (1.0 - T * K) / den};
}

std::complex<double> discrete_phase_lead_response(const DiscretePhaseLeadParameters& parameters, double dt_s,
                                                  double omega_rad_s) {
  const double K = tustin_warping_constant(parameters, dt_s);
  return phase_lead_response(parameters.network, K * std::tan(0.5 * omega_rad_s * dt_s));
}

DiscretePhaseLeadCompensator::DiscretePhaseLeadCompensator(const DiscretePhaseLeadParameters& parameters)
    : parameters_(parameters) {
  parameters_.network.validate();
}

void DiscretePhaseLeadCompensator::configure(double dt_s) {
  section_ = tustin_phase_lead(parameters_, dt_s);
  const bool identity = parameters_.network.time_constant_s == 0.0 || parameters_.network.ratio_a == 1.0;
  low_frequency_lead_s_ =
      identity ? 0.0
               : parameters_.network.low_frequency_lead_s() * tustin_warping_constant(parameters_, dt_s) * dt_s / 2.0;
  reset(0.0);
}

void DiscretePhaseLeadCompensator::reset(double initial_displacement_m) noexcept {
  // DC gain is 1: at rest the input and the output both equal the held displacement.
  previous_input_m_ = initial_displacement_m;
  previous_output_m_ = initial_displacement_m;
}

DiscretePhaseLeadParameters DiscretePhaseLeadParameters::read(config::Source& section) {
  const double delay_s = section.number("delay_s", {"s", "the delay to compensate: (a - 1) T", 0.0, 1.0, true});
  const double ratio_a = section.number("ratio_a", {"", "a, the network's high-frequency gain", 0.0, 100.0, true});
  const double prewarp_hz =
      section.number_or("prewarp_frequency_hz", 0.0,
                        config::Number::between(0.0, 1e4, "Hz", "Tustin exact at this frequency (0: plain Tustin)"));
  return for_delay(delay_s, ratio_a, prewarp_hz);
}

}  // namespace rpsd::compensation
