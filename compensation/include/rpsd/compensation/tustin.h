// The bilinear (Tustin) map of a continuous transfer function N(s)/D(s) to a discrete filter:
// s = K (1 - q) / (1 + q), q = z^-1, K = 2 / dt (or w_p / tan(w_p dt / 2), exact at the
// pre-warping frequency w_p). It maps the left half-plane into the unit disc, a pole or zero
// p to z = (K + p) / (K - p), and the zeros at infinity of a strictly proper N/D to z = -1.
#pragma once

#include <complex>
#include <vector>

namespace rpsd::compensation {

// A continuous transfer function by its coefficients in descending powers of s:
// (n_0 s^m + ... + n_m) / (d_0 s^n + ... + d_n), m <= n, d_0 != 0.
struct ContinuousTransferFunction {
  std::vector<double> numerator;
  std::vector<double> denominator;
};

// y[k] = b_0 x[k] + ... + b_n x[k-n] - a_1 y[k-1] - ... - a_n y[k-n]; a_0 = 1.
struct DiscreteFilterCoefficients {
  std::vector<double> b;
  std::vector<double> a;
};

// K of the map: 2 / dt_s, or pre-warped so that the map is exact at prewarp_frequency_hz
// (0: none). Real-time safe.
double tustin_constant(double dt_s, double prewarp_frequency_hz);

// The discrete filter of `tf` at step dt_s. Throws std::invalid_argument naming the problem
// (an improper or empty transfer function, a zero leading coefficient, a non-finite one).
// Not real-time safe.
DiscreteFilterCoefficients tustin(const ContinuousTransferFunction& tf, double dt_s, double prewarp_frequency_hz = 0.0);

// N(s)/D(s) at s. Real-time safe.
std::complex<double> evaluate(const ContinuousTransferFunction& tf, std::complex<double> s);

// The discrete filter's response at z = e^{j w dt}. Real-time safe.
std::complex<double> discrete_response(const DiscreteFilterCoefficients& f, double omega_rad_s, double dt_s);

// The roots of a polynomial in descending powers (of s, or of z for b and a read as
// z^n (b_0 + b_1 z^-1 + ...)). Not real-time safe.
std::vector<std::complex<double>> polynomial_roots(const std::vector<double>& descending);

}  // namespace rpsd::compensation
