#include "rpsd/integrators/amplification.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rpsd::integrators {

Eigen::Matrix3d amplification_matrix(const IntegratorConfig& config, double omega_dt, double damping_ratio) {
  if (!(omega_dt > 0.0)) throw std::invalid_argument("omega_dt must be > 0");
  if (!(damping_ratio >= 0.0)) throw std::invalid_argument("damping ratio must be >= 0");
  auto integrator = make_integrator(config);
  // SDOF with omega = 1 rad/s: m = 1, k = 1, c = 2 xi, so dt = Omega.
  const double k = 1.0;
  const auto m = StructuralMatrices::dense(Eigen::MatrixXd::Constant(1, 1, 1.0),
                                           Eigen::MatrixXd::Constant(1, 1, 2.0 * damping_ratio),
                                           Eigen::MatrixXd::Constant(1, 1, k));
  integrator->configure(m, omega_dt, ConfigureOptions{false});
  // Unit states in the natural scale of the SDOF (x ~ v/omega ~ a/omega^2, omega = 1).
  const Eigen::Vector3d scale(1.0, 1.0, 1.0);
  Eigen::Matrix3d A;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
  Eigen::VectorXd r(1);
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e = scale(j) * Eigen::Vector3d::Unit(j);
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, e(0));
    integrator->set_state(x, Eigen::VectorXd::Constant(1, e(1)), Eigen::VectorXd::Constant(1, e(2)), k * x, zero);
    integrator->begin_step(zero);
    for (int i = 0; i < integrator->iterations_per_step(); ++i) {
      r = k * integrator->target_displacement();
      integrator->set_measured_restoring_force(r);
    }
    integrator->end_step();
    A(0, j) = integrator->displacement()(0) / scale(j);
    A(1, j) = integrator->velocity()(0) / scale(j);
    A(2, j) = integrator->acceleration()(0) / scale(j);
  }
  return A;
}

AmplificationPoint analyze_amplification(const IntegratorConfig& config, double omega_dt, double damping_ratio) {
  const Eigen::Matrix3d A = amplification_matrix(config, omega_dt, damping_ratio);
  Eigen::EigenSolver<Eigen::Matrix3d> es(A, false);
  AmplificationPoint p;
  p.omega_dt = omega_dt;
  p.damping_ratio = damping_ratio;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p.period_ratio = p.numerical_damping_ratio = p.algorithmic_damping_ratio = nan;
  int principal = -1;
  for (int i = 0; i < 3; ++i) {
    p.eigenvalues[static_cast<std::size_t>(i)] = es.eigenvalues()(i);
    const double mod = std::abs(es.eigenvalues()(i));
    p.spectral_radius = std::max(p.spectral_radius, mod);
    // The principal pair is the complex one (imaginary part beyond round-off).
    if (std::abs(es.eigenvalues()(i).imag()) > 1e-12 * std::max(1.0, mod) && es.eigenvalues()(i).imag() > 0.0)
      principal = i;
  }
  if (principal >= 0) {
    // Hilber-Hughes convention, as in the reference tables: lambda = exp(Omega_bar (-xi_bar
    // +- i)), so Omega_bar = arg(lambda) and xi_bar = -ln|lambda| / Omega_bar.
    const std::complex<double> lambda = es.eigenvalues()(principal);
    const double omega_bar = std::arg(lambda);
    p.oscillatory = true;
    p.period_ratio = omega_dt / omega_bar;
    p.numerical_damping_ratio = -std::log(std::abs(lambda)) / omega_bar;
    p.algorithmic_damping_ratio =
        p.numerical_damping_ratio - damping_ratio / std::sqrt(1.0 - damping_ratio * damping_ratio);
  }
  return p;
}

double numerical_stability_limit(const IntegratorConfig& config, double damping_ratio, double omega_dt_max) {
  // Near Omega_cr the principal pair is almost a double root, whose computed modulus
  // carries an error of order sqrt(machine epsilon).
  constexpr double tol = 1e-7;
  auto stable = [&](double w) { return analyze_amplification(config, w, damping_ratio).spectral_radius <= 1.0 + tol; };
  double lo = 0.0;
  double hi = std::numeric_limits<double>::infinity();
  // Geometric scan from 0.01: fine enough to find the first unstable Omega.
  for (double w = 0.01; w <= omega_dt_max * (1.0 + 1e-12); w *= 1.02) {
    if (stable(w)) {
      lo = w;
    } else {
      hi = w;
      break;
    }
  }
  if (!std::isfinite(hi)) return std::numeric_limits<double>::infinity();
  for (int i = 0; i < 60 && hi - lo > 1e-10 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace rpsd::integrators
