#pragma once
// Spectral properties of a scheme from the 3x3 amplification matrix on (x, v, a) of a
// linear SDOF (omega = 1 rad/s, damping ratio xi, dt = Omega). The matrix is built by
// stepping the actual implementation from the unit states, so the analysis checks the
// code, not a re-derivation.
#include "rpsd/integrators/factory.h"

#include <Eigen/Dense>

#include <array>
#include <complex>

namespace rpsd::integrators {

// Not real-time safe. Columns: state at t + dt from (1,0,0), (0,1,0), (0,0,1) at t.
Eigen::Matrix3d amplification_matrix(const IntegratorConfig& config, double omega_dt, double damping_ratio);

struct AmplificationPoint {
  double omega_dt = 0.0;
  double damping_ratio = 0.0;  // physical xi of the SDOF
  std::array<std::complex<double>, 3> eigenvalues{};
  double spectral_radius = 0.0;  // max |lambda| over all three eigenvalues
  // The principal roots are a complex pair, written as in Hilber & Hughes (and the
  // reference tables) lambda = exp(Omega_bar (-xi_bar +- i)): Omega_bar = arg(lambda).
  // For a damped SDOF the exact solution then has T_bar/T = 1/sqrt(1-xi^2) and
  // xi_bar = xi/sqrt(1-xi^2).
  bool oscillatory = false;
  double period_ratio = 0.0;               // T_bar/T = Omega / Omega_bar (NaN if not oscillatory)
  double numerical_damping_ratio = 0.0;    // xi_bar = -ln|lambda| / Omega_bar (includes physical)
  double algorithmic_damping_ratio = 0.0;  // xi_bar minus the exact xi/sqrt(1-xi^2)
};

// Not real-time safe.
AmplificationPoint analyze_amplification(const IntegratorConfig& config, double omega_dt, double damping_ratio);

// Largest Omega with spectral radius <= 1 + 1e-7, found by scanning Omega up to
// omega_dt_max and bisecting; +infinity if the scheme is stable over the whole range.
double numerical_stability_limit(const IntegratorConfig& config, double damping_ratio, double omega_dt_max = 1000.0);

}  // namespace rpsd::integrators
