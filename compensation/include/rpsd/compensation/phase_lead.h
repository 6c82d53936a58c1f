// First-order phase-lead network G_c(s) = (1 + a T s) / (1 + T s), a > 1: the seed paper's
// compensator for amplitude reduction and response delay (Zhao et al. 2003).
#pragma once

#include <complex>

namespace rpsd::compensation {

struct PhaseLeadParameters {
  double ratio_a = 1.0;          ///< a > 1: high-frequency gain of the network
  double time_constant_s = 0.0;  ///< T: the pole at 1/T, the zero at 1/(a T)

  /// Throws std::invalid_argument unless a >= 1 and T >= 0. Not real-time safe.
  void validate() const;
  /// Maximum phase lead asin((a - 1) / (a + 1)), radians.
  double max_phase_lead_rad() const;
  /// Frequency of the maximum phase lead 1 / (T sqrt(a)), rad/s.
  double max_lead_frequency_rad_s() const;
  /// Low-frequency delay compensated: d(phase)/d(omega) at 0 = (a - 1) T, seconds.
  double low_frequency_lead_s() const { return (ratio_a - 1.0) * time_constant_s; }
};

/// The network whose zero cancels a first-order lag of time constant lag_time_constant_s
/// (a T = T_lag), leaving a pole at a / T_lag: the amplitude compensation of Figure 6.
PhaseLeadParameters cancel_first_order_lag(double lag_time_constant_s, double ratio_a);

/// G_c(j omega). Real-time safe.
std::complex<double> phase_lead_response(const PhaseLeadParameters& lead, double omega_rad_s);

}  // namespace rpsd::compensation
