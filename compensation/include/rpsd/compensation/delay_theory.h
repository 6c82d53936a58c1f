// What a delay does to an SDOF hybrid test (reference sheet section 3): the exact roots of
// the delay-differential equation m x'' + c x' + k_n x + k_e x(t - tau) = 0 and the
// first-order estimate zeta_eff = zeta - (k_e / k) omega_n tau / 2. Not real-time safe.
#pragma once

#include <complex>

namespace rpsd::compensation {

struct DelayedOscillator {
  double mass_kg = 0.0;
  double damping_n_s_per_m = 0.0;
  double numerical_stiffness_n_per_m = 0.0;     // k_n, undelayed
  double experimental_stiffness_n_per_m = 0.0;  // k_e, acting through the delay
};

// The dominant oscillatory root s of m s^2 + c s + k_n + k_e e^{-s tau} = 0 (Newton from the
// undelayed root, continued in tau). A negative tau is a lead (over-compensation).
std::complex<double> dominant_root(const DelayedOscillator& system, double delay_s);

// Damping ratio of a root: -Re(s) / |s|.
double damping_ratio_of(std::complex<double> root);

// zeta - (k_e / k) omega_n tau / 2, the small-delay estimate.
double approximate_damping_ratio(const DelayedOscillator& system, double delay_s);

// Smallest delay at which the system loses stability (a root on the imaginary axis); +inf
// when it is stable for every delay.
double critical_delay_s(const DelayedOscillator& system);

}  // namespace rpsd::compensation
