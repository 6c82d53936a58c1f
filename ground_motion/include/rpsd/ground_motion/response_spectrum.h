// Linear SDOF response to a ground-acceleration record, u'' + 2 zeta omega u' + omega^2 u = -a_g(t)
// from rest (u relative to the ground), exact for acceleration linear between samples (Nigam & Jennings
// 1969), and response spectra built on it. The step map is the exponential of the augmented matrix: no
// cancellation at small omega h, valid for every zeta >= 0.
// Derivation: docs/ground-motions.md
#pragma once

#include <cstddef>
#include <vector>

#include "rpsd/ground_motion/record.h"

namespace rpsd::ground_motion {

class PiecewiseLinearSdof {
 public:
  struct Coefficients {
    double a_uu, a_uv, a_vu, a_vv;  // free response over one step
    double b_u0, b_u1, b_v0, b_v1;  // weights of a_g at the start and end of the step
  };

  // omega > 0, zeta >= 0, h > 0 (all finite); throws std::invalid_argument otherwise.
  // Not real-time safe (may throw); allocates nothing.
  PiecewiseLinearSdof(double omega_rad_per_s, double zeta, double h_s);

  // Advances (u, v) over one step with ground acceleration a0 -> a1. Real-time safe.
  void step(double& u_m, double& v_m_per_s, double a0_m_per_s2, double a1_m_per_s2) const noexcept {
    const double u = u_m;
    const double v = v_m_per_s;
    u_m = c_.a_uu * u + c_.a_uv * v + c_.b_u0 * a0_m_per_s2 + c_.b_u1 * a1_m_per_s2;
    v_m_per_s = c_.a_vu * u + c_.a_vv * v + c_.b_v0 * a0_m_per_s2 + c_.b_v1 * a1_m_per_s2;
  }

  const Coefficients& coefficients() const { return c_; }

 private:
  Coefficients c_{};
};

// Relative displacement u(t_i) at every sample of the record, from rest. Exact for the
// piecewise-linear record (errors are round-off only). Not real-time safe.
std::vector<double> sdof_response_piecewise_linear(const GroundMotionRecord& record, double omega_rad_per_s,
                                                   double zeta);

struct ResponseSpectrumOptions {
  std::vector<double> periods_s;  // each > 0
  double damping_ratio = 0.05;
  // The peak is searched at sub-steps of at most this fraction of the oscillator period
  // (exact, since the record is linear within a step), so short periods whose peak falls
  // between samples are not underestimated. 1/20 keeps the peak within 1.3 % at worst
  // (1 - cos(pi/20)) and usually far closer.
  double max_substep_fraction_of_period = 0.05;
};

// Peaks over the record's duration (pad() the record to include free vibration after it).
struct ResponseSpectrum {
  std::vector<double> periods_s;
  double damping_ratio = 0.05;
  std::vector<double> displacement_m;                // Sd = max |u|
  std::vector<double> pseudo_velocity_m_per_s;       // omega Sd
  std::vector<double> pseudo_acceleration_m_per_s2;  // omega^2 Sd
};

// Not real-time safe. Throws std::invalid_argument for a bad period or damping.
ResponseSpectrum response_spectrum(const GroundMotionRecord& record, const ResponseSpectrumOptions& options);

// `count` periods from first_s to last_s, equally spaced in log(T) (count >= 2, 0 < first < last).
std::vector<double> log_spaced_periods(double first_s, double last_s, std::size_t count);

}  // namespace rpsd::ground_motion
