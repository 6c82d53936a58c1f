// Exact piecewise-linear SDOF solution and response spectra, against closed forms:
// Nigam-Jennings coefficients (Chopra, Dynamics of Structures, Table 5.2.1), the response to
// a ground acceleration linear in time, and the steady-state amplitude under a sine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/processing.h"
#include "rpsd/ground_motion/response_spectrum.h"
#include "test_files.h"

namespace rpsd::ground_motion {
namespace {

constexpr double pi = std::numbers::pi;

// Chopra Table 5.2.1 for m = 1, k = w^2 (force p = -a_g), zeta < 1:
//   u+ = A u + B v + C p0 + D p1,   v+ = A' u + B' v + C' p0 + D' p1.
struct ClosedForm {
  double A, B, C, D, Ap, Bp, Cp, Dp;
};
ClosedForm nigam_jennings(double w, double z, double h) {
  const double k = w * w;
  const double r = std::sqrt(1.0 - z * z);
  const double wd = w * r;
  const double e = std::exp(-z * w * h);
  const double s = std::sin(wd * h);
  const double c = std::cos(wd * h);
  ClosedForm f{};
  f.A = e * (z / r * s + c);
  f.B = e * (s / wd);
  f.C = (2.0 * z / (w * h) + e * (((1.0 - 2.0 * z * z) / (wd * h) - z / r) * s - (1.0 + 2.0 * z / (w * h)) * c)) / k;
  f.D = (1.0 - 2.0 * z / (w * h) + e * ((2.0 * z * z - 1.0) / (wd * h) * s + 2.0 * z / (w * h) * c)) / k;
  f.Ap = -e * (w / r * s);
  f.Bp = e * (c - z / r * s);
  f.Cp = (-1.0 / h + e * ((w / r + z / (h * r)) * s + c / h)) / k;
  f.Dp = (1.0 - e * (z / r * s + c)) / (k * h);
  return f;
}

TEST(GroundMotionSdof, CoefficientsEqualTheClosedFormNigamJennings) {
  for (const auto& [w, z, h] : {std::tuple{2.0 * pi, 0.05, 0.02}, std::tuple{10.0, 0.2, 0.1},
                                std::tuple{2.0 * pi / 0.05, 0.02, 0.01}, std::tuple{0.7, 0.9, 0.05}}) {
    SCOPED_TRACE(::testing::Message() << "w " << w << " zeta " << z << " h " << h);
    const auto f = nigam_jennings(w, z, h);
    const PiecewiseLinearSdof::Coefficients c = PiecewiseLinearSdof(w, z, h).coefficients();
    const double tol = 1e-11;
    EXPECT_NEAR(c.a_uu, f.A, tol);
    EXPECT_NEAR(c.a_uv, f.B, tol * h);
    EXPECT_NEAR(c.a_vu, f.Ap, tol * w * w * h);
    EXPECT_NEAR(c.a_vv, f.Bp, tol);
    EXPECT_NEAR(c.b_u0, -f.C, tol * h * h);
    EXPECT_NEAR(c.b_u1, -f.D, tol * h * h);
    EXPECT_NEAR(c.b_v0, -f.Cp, tol * h);
    EXPECT_NEAR(c.b_v1, -f.Dp, tol * h);
  }
}

// u'' + 2 z w u' + w^2 u = -c t from rest:
//   u = -c t / w^2 + 2 z c / w^3 + e^(-z w t) (A cos wd t + B sin wd t),
//   A = -2 z c / w^3,  B = c (1 - 2 z^2) / (w^2 wd).
double ramp_response(double c, double w, double z, double t) {
  const double wd = w * std::sqrt(1.0 - z * z);
  const double a = -2.0 * z * c / (w * w * w);
  const double b = c * (1.0 - 2.0 * z * z) / (w * w * wd);
  return -c * t / (w * w) + 2.0 * z * c / (w * w * w) +
         std::exp(-z * w * t) * (a * std::cos(wd * t) + b * std::sin(wd * t));
}

TEST(GroundMotionSdof, ExactForGroundAccelerationLinearInTime) {
  GroundMotionRecord ramp;
  ramp.source = "ramp";
  ramp.dt_s = 0.02;  // a coarse step on purpose: the solution is exact at any step
  const double c = 0.7;
  for (int i = 0; i <= 1000; ++i) ramp.acceleration_m_per_s2.push_back(c * i * ramp.dt_s);
  for (const double z : {0.0, 0.02, 0.05, 0.3, 0.9}) {
    for (const double period : {0.05, 0.5, 3.0}) {
      const double w = 2.0 * pi / period;
      const auto u = sdof_response_piecewise_linear(ramp, w, z);
      ASSERT_EQ(u.size(), ramp.size());
      EXPECT_EQ(u[0], 0.0);
      double worst = 0.0;
      double largest = 0.0;
      for (std::size_t i = 0; i < u.size(); ++i) {
        const double exact = ramp_response(c, w, z, static_cast<double>(i) * ramp.dt_s);
        worst = std::max(worst, std::abs(u[i] - exact));
        largest = std::max(largest, std::abs(exact));
      }
      EXPECT_LT(worst, 1e-10 * largest) << "zeta " << z << " T " << period;
    }
  }
}

TEST(GroundMotionSdof, LinearUpsamplingDoesNotChangeTheExactResponse) {
  // The record's piecewise-linear signal is the same after resample() by an integer factor,
  // so the exact response at the original samples must agree to round-off.
  const auto record = read_peer_at2(testing::shared_record("I-ELC180.AT2"));
  ResampleOptions o;
  o.dt_s = record.dt_s / 8.0;
  const auto fine = resample(record, o);
  const double w = 2.0 * pi / 0.7;
  const auto coarse_u = sdof_response_piecewise_linear(record, w, 0.05);
  const auto fine_u = sdof_response_piecewise_linear(fine, w, 0.05);
  double worst = 0.0;
  double largest = 0.0;
  for (std::size_t i = 0; i < coarse_u.size(); ++i) {
    worst = std::max(worst, std::abs(coarse_u[i] - fine_u[8 * i]));
    largest = std::max(largest, std::abs(coarse_u[i]));
  }
  EXPECT_LT(worst, 1e-11 * largest);
}

TEST(GroundMotionResponseSpectrum, SineMatchesTheSteadyStateAmplitude) {
  // a_g = sin(W t) at 1 Hz, ramped in over 40 s by the C2 smoothstep 6x^5 - 15x^4 + 10x^3
  // (so almost no free vibration is excited), then 100 s steady:
  // Sd = 1 / sqrt((w^2 - W^2)^2 + (2 z w W)^2).
  // Expected departures: the linear interpolation of a sine sampled at dt = 0.005 s keeps
  // sinc^2(W dt / 2) = 1 - 8e-5 of its amplitude; the peak is sampled every <= 0.005 s
  // (1 - cos(W dt / 2) = 1.2e-4): together at most 2e-4 low, plus any ramp transient.
  GroundMotionRecord sine;
  sine.source = "sine";
  sine.dt_s = 0.005;
  const double big_w = 2.0 * pi;
  for (int i = 0; i <= 28000; ++i) {
    const double t = i * sine.dt_s;
    const double x = std::min(t / 40.0, 1.0);
    const double ramp = x * x * x * (10.0 - 15.0 * x + 6.0 * x * x);
    sine.acceleration_m_per_s2.push_back(ramp * std::sin(big_w * t));
  }
  ResponseSpectrumOptions o;
  o.periods_s = {0.1, 0.3, 0.7, 1.0, 1.5, 3.0, 5.0};
  const auto spectrum = response_spectrum(sine, o);
  ASSERT_EQ(spectrum.displacement_m.size(), o.periods_s.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < o.periods_s.size(); ++i) {
    const double w = 2.0 * pi / o.periods_s[i];
    const double theory = 1.0 / std::sqrt(std::pow(w * w - big_w * big_w, 2) + std::pow(2.0 * 0.05 * w * big_w, 2));
    const double error = spectrum.displacement_m[i] / theory - 1.0;
    worst = std::max(worst, std::abs(error));
    EXPECT_NEAR(error, 0.0, 3e-4) << "T " << o.periods_s[i];  // measured: at most 1.3e-4
    EXPECT_DOUBLE_EQ(spectrum.pseudo_acceleration_m_per_s2[i], w * w * spectrum.displacement_m[i]);
    EXPECT_DOUBLE_EQ(spectrum.pseudo_velocity_m_per_s[i], w * spectrum.displacement_m[i]);
  }
  RecordProperty("sine_spectrum_worst_relative_error", std::to_string(worst));
}

TEST(GroundMotionResponseSpectrum, ShortPeriodPseudoAccelerationTendsToThePga) {
  // A very stiff oscillator follows the ground: PSA(T -> 0) -> PGA. El Centro's content is
  // below ~25 Hz, so at T = 0.005 s (200 Hz) the dynamic amplification is (25/200)^2 ~ 1.6 %
  // at most for its highest components.
  const auto record = read_peer_at2(testing::shared_record("I-ELC180.AT2"));
  ResponseSpectrumOptions o;
  o.periods_s = {0.005};
  const auto spectrum = response_spectrum(record, o);
  const double pga = std::abs(peak_ground_acceleration(record).value_m_per_s2);
  EXPECT_NEAR(spectrum.pseudo_acceleration_m_per_s2[0] / pga, 1.0, 0.016);
  RecordProperty("psa_0005_over_pga", std::to_string(spectrum.pseudo_acceleration_m_per_s2[0] / pga));
}

TEST(GroundMotionResponseSpectrum, LogSpacedPeriods) {
  const auto periods = log_spaced_periods(0.02, 10.0, 50);
  ASSERT_EQ(periods.size(), 50u);
  EXPECT_DOUBLE_EQ(periods.front(), 0.02);
  EXPECT_EQ(periods.back(), 10.0);
  EXPECT_NEAR(periods[1] / periods[0], periods[49] / periods[48], 1e-12);
  EXPECT_THROW(log_spaced_periods(1.0, 0.5, 10), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::ground_motion
