#pragma once
// Closed-form response of m x'' + c x' + k x = f0 sin(wf t) with x(0) = x0, x'(0) = v0,
// written with omega = sqrt(k/m), xi = c/(2 m omega), p0 = f0/m.
#include <cmath>

namespace rpsd::integrators::test {

struct SdofExact {
  double omega, xi, x0, v0, p0 = 0.0, omega_f = 0.0;

  // Free response of the homogeneous equation from (xh0, vh0).
  double free(double xh0, double vh0, double t) const {
    const double wd = omega * std::sqrt(1.0 - xi * xi);
    return std::exp(-xi * omega * t) * (xh0 * std::cos(wd * t) + (vh0 + xi * omega * xh0) / wd * std::sin(wd * t));
  }
  double operator()(double t) const {
    if (p0 == 0.0) return free(x0, v0, t);
    const double r = omega_f / omega;
    const double amp = p0 / (omega * omega) / std::hypot(1.0 - r * r, 2.0 * xi * r);
    const double phi = std::atan2(2.0 * xi * r, 1.0 - r * r);
    const double xp0 = -amp * std::sin(phi);
    const double vp0 = amp * omega_f * std::cos(phi);
    return amp * std::sin(omega_f * t - phi) + free(x0 - xp0, v0 - vp0, t);
  }
};

}  // namespace rpsd::integrators::test
