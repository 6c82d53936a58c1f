#include "rpsd/ground_motion/response_spectrum.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "small_matrix.h"

namespace rpsd::ground_motion {

PiecewiseLinearSdof::PiecewiseLinearSdof(double omega, double zeta, double h) {
  if (!(omega > 0.0) || !std::isfinite(omega) || !(zeta >= 0.0) || !std::isfinite(zeta) || !(h > 0.0) ||
      !std::isfinite(h)) {
    throw std::invalid_argument("PiecewiseLinearSdof: expected omega > 0, zeta >= 0, h > 0, got " +
                                std::to_string(omega) + ", " + std::to_string(zeta) + ", " + std::to_string(h));
  }
  // Balanced state z = (omega u, v): z' = omega [[0, 1], [-1, -2 zeta]] z + (0, -1) a_g.
  // Augmented with the load p = a_g and its increment q over the step (p' = q / h), in
  // step-normalised time: exp of
  //   [ F h   G h   0 ]
  //   [ 0     0     1 ]
  //   [ 0     0     0 ]
  // maps (z, a0, a1 - a0) to (z+, a1, a1 - a0).
  detail::SquareMatrix<4> m{};
  const double wh = omega * h;
  m[0][1] = wh;
  m[1][0] = -wh;
  m[1][1] = -2.0 * zeta * wh;
  m[1][2] = -h;
  m[2][3] = 1.0;
  const auto e = detail::matrix_exponential(m);
  // Back to (u, v): u = z0 / omega.
  c_.a_uu = e[0][0];
  c_.a_uv = e[0][1] / omega;
  c_.a_vu = e[1][0] * omega;
  c_.a_vv = e[1][1];
  const double g0_u = e[0][2] / omega;
  const double g1_u = e[0][3] / omega;
  const double g0_v = e[1][2];
  const double g1_v = e[1][3];
  c_.b_u0 = g0_u - g1_u;
  c_.b_u1 = g1_u;
  c_.b_v0 = g0_v - g1_v;
  c_.b_v1 = g1_v;
}

std::vector<double> sdof_response_piecewise_linear(const GroundMotionRecord& record, double omega_rad_per_s,
                                                   double zeta) {
  const auto& a = record.acceleration_m_per_s2;
  std::vector<double> u(a.size(), 0.0);
  if (a.size() < 2) return u;
  const PiecewiseLinearSdof sdof(omega_rad_per_s, zeta, record.dt_s);
  double d = 0.0;
  double v = 0.0;
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    sdof.step(d, v, a[i], a[i + 1]);
    u[i + 1] = d;
  }
  return u;
}

ResponseSpectrum response_spectrum(const GroundMotionRecord& record, const ResponseSpectrumOptions& options) {
  if (!(options.damping_ratio >= 0.0) || !std::isfinite(options.damping_ratio)) {
    throw std::invalid_argument(record.source + ": response spectrum damping ratio must be >= 0");
  }
  if (!(options.max_substep_fraction_of_period > 0.0) || !(options.max_substep_fraction_of_period <= 1.0)) {
    throw std::invalid_argument(record.source + ": max_substep_fraction_of_period must be in (0, 1]");
  }
  if (!(record.dt_s > 0.0)) throw std::invalid_argument(record.source + ": dt must be > 0");
  const auto& a = record.acceleration_m_per_s2;
  ResponseSpectrum out;
  out.periods_s = options.periods_s;
  out.damping_ratio = options.damping_ratio;
  for (const double period : options.periods_s) {
    if (!(period > 0.0) || !std::isfinite(period)) {
      throw std::invalid_argument(record.source + ": response spectrum period must be > 0, got " +
                                  std::to_string(period));
    }
    const double omega = 2.0 * std::numbers::pi / period;
    const double substeps_real = std::ceil(record.dt_s / (options.max_substep_fraction_of_period * period));
    const auto substeps = static_cast<std::size_t>(std::max(1.0, substeps_real));
    const double h = record.dt_s / static_cast<double>(substeps);
    const PiecewiseLinearSdof sdof(omega, options.damping_ratio, h);
    double u = 0.0;
    double v = 0.0;
    double peak = 0.0;
    for (std::size_t i = 0; i + 1 < a.size(); ++i) {
      const double slope = (a[i + 1] - a[i]) / static_cast<double>(substeps);
      for (std::size_t j = 0; j < substeps; ++j) {
        const double a0 = a[i] + slope * static_cast<double>(j);
        const double a1 = j + 1 == substeps ? a[i + 1] : a[i] + slope * static_cast<double>(j + 1);
        sdof.step(u, v, a0, a1);
        peak = std::max(peak, std::abs(u));
      }
    }
    out.displacement_m.push_back(peak);
    out.pseudo_velocity_m_per_s.push_back(omega * peak);
    out.pseudo_acceleration_m_per_s2.push_back(omega * omega * peak);
  }
  return out;
}

std::vector<double> log_spaced_periods(double first_s, double last_s, std::size_t count) {
  if (!(first_s > 0.0) || !(last_s > first_s) || !std::isfinite(last_s) || count < 2) {
    throw std::invalid_argument("log_spaced_periods: expected 0 < first < last and count >= 2");
  }
  std::vector<double> periods(count);
  const double ratio = std::log(last_s / first_s) / static_cast<double>(count - 1);
  for (std::size_t i = 0; i < count; ++i) {
    periods[i] = first_s * std::exp(ratio * static_cast<double>(i));
  }
  periods.back() = last_s;
  return periods;
}

}  // namespace rpsd::ground_motion
