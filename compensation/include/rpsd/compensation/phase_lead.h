// First-order phase-lead network G_c(s) = (1 + a T s) / (1 + T s), a > 1: the seed paper's
// compensator for amplitude reduction and response delay (Zhao et al. 2003).
#pragma once

#include <complex>

namespace rpsd::compensation {

struct PhaseLeadParameters {
  double ratio_a = 1.0;          // a > 1: high-frequency gain of the network
  double time_constant_s = 0.0;  // T: the pole at 1/T, the zero at 1/(a T)

  // Throws std::invalid_argument unless a >= 1 and T >= 0. Not real-time safe.
  void validate() const;
  // Maximum phase lead asin((a - 1) / (a + 1)), radians.
  double max_phase_lead_rad() const;
  // Frequency of the maximum phase lead 1 / (T sqrt(a)), rad/s.
  double max_lead_frequency_rad_s() const;
  // Low-frequency delay compensated: d(phase)/d(omega) at 0 = (a - 1) T, seconds.
  double low_frequency_lead_s() const { return (ratio_a - 1.0) * time_constant_s; }
};

// The network whose zero cancels a first-order lag of time constant lag_time_constant_s
// (a T = T_lag), leaving a pole at a / T_lag: the amplitude compensation of Figure 6.
PhaseLeadParameters cancel_first_order_lag(double lag_time_constant_s, double ratio_a);

// G_c(j omega). Real-time safe.
std::complex<double> phase_lead_response(const PhaseLeadParameters& lead, double omega_rad_s);

// Design from a target delay tau. The network's phase is atan(a T w) - atan(T w)
// = (a - 1) T w - O(w^3): below its pole 1/T it is a pure time advance of (a - 1) T, so the
// design rule is (a - 1) T = tau, with either a or T chosen. (The price is a gain that rises
// from 1 towards a; choose a small a for a gentle rise, a large a for a fast pole.)
// A zero delay gives the identity network (T = 0). All throw std::invalid_argument with the
// offending value. Not real-time safe.

// (a - 1) T = delay_s with the chosen ratio a > 1: T = delay_s / (a - 1).
PhaseLeadParameters phase_lead_for_delay(double delay_s, double ratio_a);

// (a - 1) T = delay_s with the chosen time constant T > 0: a = 1 + delay_s / T.
PhaseLeadParameters phase_lead_for_delay_with_time_constant(double delay_s, double time_constant_s);

// The seed paper's frequency-domain rule: the maximum lead asin((a - 1) / (a + 1)), at
// w_m = 1 / (T sqrt(a)), placed at the dominant frequency w_d = 2 pi frequency_hz and equal
// to w_d delay_s (requires 0 <= w_d delay_s < pi / 2): a = (1 + sin phi) / (1 - sin phi),
// T = 1 / (w_d sqrt(a)). Exact at w_d; its low-frequency lead (a - 1) T differs from delay_s.
PhaseLeadParameters phase_lead_peaking_at(double delay_s, double frequency_hz);

}  // namespace rpsd::compensation
