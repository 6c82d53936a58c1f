#include "rpsd/compensation/delay_theory.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rpsd::compensation {
namespace {

using Complex = std::complex<double>;

Complex newton(const DelayedOscillator& p, double tau, Complex s) {
  for (int i = 0; i < 100; ++i) {
    const Complex e = std::exp(-s * tau);
    const Complex f = p.mass_kg * s * s + p.damping_n_s_per_m * s + p.numerical_stiffness_n_per_m +
                      p.experimental_stiffness_n_per_m * e;
    const Complex df = 2.0 * p.mass_kg * s + p.damping_n_s_per_m - tau * p.experimental_stiffness_n_per_m * e;
    const Complex step = f / df;
    s -= step;
    if (std::abs(step) < 1e-14 * std::abs(s)) return s;
  }
  throw std::runtime_error("dominant_root: Newton iteration did not converge");
}

}  // namespace

Complex dominant_root(const DelayedOscillator& p, double delay_s) {
  const double k = p.numerical_stiffness_n_per_m + p.experimental_stiffness_n_per_m;
  if (!(p.mass_kg > 0.0) || !(k > 0.0)) throw std::invalid_argument("dominant_root: needs positive mass and stiffness");
  // Undelayed root, then continuation in tau so that Newton stays on the same branch.
  const double omega_n = std::sqrt(k / p.mass_kg);
  const double zeta = p.damping_n_s_per_m / (2.0 * std::sqrt(k * p.mass_kg));
  Complex s(-zeta * omega_n, omega_n * std::sqrt(std::max(1.0 - zeta * zeta, 1e-12)));
  const int pieces = 1 + static_cast<int>(std::abs(delay_s) * omega_n / 0.05);
  for (int i = 1; i <= pieces; ++i) s = newton(p, delay_s * i / pieces, s);
  return s.imag() < 0.0 ? std::conj(s) : s;
}

double damping_ratio_of(Complex root) { return -root.real() / std::abs(root); }

double approximate_damping_ratio(const DelayedOscillator& p, double delay_s) {
  const double k = p.numerical_stiffness_n_per_m + p.experimental_stiffness_n_per_m;
  const double omega_n = std::sqrt(k / p.mass_kg);
  const double zeta = p.damping_n_s_per_m / (2.0 * std::sqrt(k * p.mass_kg));
  return zeta - p.experimental_stiffness_n_per_m / k * omega_n * delay_s / 2.0;
}

double critical_delay_s(const DelayedOscillator& p) {
  // On s = i W: (m W^2 - k_n)^2 + c^2 W^2 = k_e^2, a quadratic in W^2; the delay is the
  // smallest theta / W with theta = atan2(c W, m W^2 - k_n) in (0, 2 pi).
  const double m = p.mass_kg, c = p.damping_n_s_per_m, kn = p.numerical_stiffness_n_per_m,
               ke = p.experimental_stiffness_n_per_m;
  const double a = m * m, b = c * c - 2.0 * m * kn, q = kn * kn - ke * ke;
  const double discriminant = b * b - 4.0 * a * q;
  if (discriminant < 0.0) return std::numeric_limits<double>::infinity();
  double best = std::numeric_limits<double>::infinity();
  for (double sign : {1.0, -1.0}) {
    const double w2 = (-b + sign * std::sqrt(discriminant)) / (2.0 * a);
    if (w2 <= 0.0) continue;
    const double w = std::sqrt(w2);
    double theta = std::atan2(c * w, m * w2 - kn);
    if (theta <= 0.0) theta += 2.0 * std::numbers::pi;
    best = std::min(best, theta / w);
  }
  return best;
}

}  // namespace rpsd::compensation
