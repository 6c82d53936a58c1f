// The Tustin PID controller against closed forms: the trapezoidal integral, the filtered
// derivative's step and ramp responses, the warped frequency response of C(s), the closed
// loop with the RTHS benchmark plant, clamping anti-windup, reset, faults and allocations.
#include "rpsd/servo/pid_controller.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/servo/harmonic_fit.h"
#include "rpsd/servo/transfer_function_plant.h"

#include "allocation_counter.h"

namespace rpsd::servo {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPeriod = 1.0 / 4096.0;

using Complex = std::complex<double>;

// C(s) written out from the gains, independently of the controller's coefficients.
Complex continuous_controller(const PidGains& g, Complex s) {
  return g.proportional + g.integral_per_s / s + g.derivative_s * s / (g.derivative_filter_time_s * s + 1.0);
}

TEST(PidController, PureProportionalIsKpTimesError) {
  PidController pid({2.5, 0.0, 0.0, 0.0}, kPeriod);
  for (double e : {0.0, 1.0, -0.37, 1e-9, 123.0, -4.0}) {
    EXPECT_EQ(pid.update(e, -kInf, kInf), 2.5 * e) << e;
    EXPECT_FALSE(pid.saturated());
  }
  EXPECT_EQ(pid.update(1.0, -2.0, 2.0), 2.0);
  EXPECT_TRUE(pid.saturated());
  EXPECT_EQ(pid.period_s(), kPeriod);
}

// e_k = k (e_{-1} = 0): the trapezoids sum to Ki T/2 sum (2j - 1) = Ki T k^2 / 2, the exact
// integral of the ramp; a rectangular rule would give Ki T k (k + 1) / 2.
TEST(PidController, IntegralOfARampIsTheTrapezoidalRuleExactly) {
  const double ki = 3.7;
  PidController pid({0.0, ki, 0.0, 0.0}, kPeriod);
  for (int k = 0; k <= 2000; ++k) {
    const double expected = ki * kPeriod * k * k / 2.0;
    const double u = pid.update(k, -kInf, kInf);
    ASSERT_NEAR(u, expected, 1e-13 * (1.0 + expected)) << k;
    ASSERT_EQ(pid.integral(), u) << k;
  }
}

TEST(PidController, FilteredDerivativeStepAndRampResponses) {
  const double kd = 0.04, tf = 0.002;
  {
    PidController pid({0.0, 0.0, kd, tf}, kPeriod);
    const double d0 = 2.0 * kd / (2.0 * tf + kPeriod), pole = (2.0 * tf - kPeriod) / (2.0 * tf + kPeriod);
    for (int k = 0; k < 20; ++k) {
      const double expected = d0 * std::pow(pole, k);
      ASSERT_NEAR(pid.update(1.0, -kInf, kInf), expected, 1e-13 * d0) << k;
    }
  }
  {
    // A ramp e = a t: the derivative settles at Kd a.
    const double a = 0.3;
    PidController pid({0.0, 0.0, kd, tf}, kPeriod);
    double u = 0.0;
    for (int k = 0; k < 4096; ++k) u = pid.update(a * k * kPeriod, -kInf, kInf);
    EXPECT_NEAR(u, kd * a, 1e-9 * kd * a);
  }
}

// The steady-state response to a sampled sine is C at the warped s = j (2/T) tan(w T / 2).
TEST(PidController, FrequencyResponseIsTheWarpedContinuousController) {
  const PidGains gains{2.0, 95.0, 0.01, 0.001};
  for (double f : {0.5, 5.0, 50.0, 500.0, 1500.0}) {
    PidController pid(gains, kPeriod);
    const double omega = 2.0 * kPi * f;
    std::vector<double> phase, output;
    for (int k = 0; k < 40000; ++k) {
      const double u = pid.update(std::sin(omega * k * kPeriod), -kInf, kInf);
      // The integrator's start leaves a constant offset (fitted); the derivative's transient
      // decays as 0.78^k and is gone after 1000 samples.
      if (k >= 1000) {
        phase.push_back(omega * k * kPeriod);
        output.push_back(u);
      }
    }
    const HarmonicFit fit = fit_harmonic(phase, output);
    const Complex c = continuous_controller(gains, Complex(0.0, 2.0 / kPeriod * std::tan(omega * kPeriod / 2.0)));
    EXPECT_NEAR(fit.amplitude / std::abs(c), 1.0, 1e-6) << f;
    EXPECT_NEAR(std::remainder(fit.phase_rad - std::arg(c), 2.0 * kPi), 0.0, 1e-6) << f;
  }
}

// The RTHS benchmark (Silva et al. 2020): the plant from command u to displacement x, and
// its sample controller, the PI G_C(s) = 2 + 95 / s on e = r - x.
TransferFunction benchmark_plant() {
  return {Polynomial{2.18385e13}, Polynomial{2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13}};
}
const PidGains kBenchmarkPi{2.0, 95.0, 0.0, 0.0};

Complex benchmark_plant_at(Complex s) {
  const double den[] = {29.13, 1.25906e4, 8.42178e6, 2.32849e9, 5.43547e11, 2.16756e13};
  Complex d = 0.0;
  for (double c : den) d = d * s + c;
  return 2.18385e13 / d;
}

// x_k measured, u_k = C(e_k) applied at once and held for one period, the plant advanced.
struct LoopResult {
  std::vector<double> time_s, displacement_m;
};
template <typename Reference>
LoopResult run_loop(Reference reference, int samples) {
  TransferFunctionPlantParameters parameters;
  parameters.transfer_function = benchmark_plant();
  parameters.plant_rate_hz = 8.0 * 4096.0;
  TransferFunctionPlant plant(parameters);
  PidController pid(kBenchmarkPi, kPeriod);
  LoopResult result;
  for (int k = 0; k < samples; ++k) {
    const double t = k * kPeriod, x = plant.measure().displacement_m;
    result.time_s.push_back(t);
    result.displacement_m.push_back(x);
    const double u = pid.update(reference(t) - x, -kInf, kInf);
    plant.advance(u, u, kPeriod);
  }
  return result;
}

TEST(PidController, ClosedLoopWithTheBenchmarkPlantMatchesTheContinuousLoop) {
  for (double f : {1.0, 5.0, 10.0, 20.0}) {
    const double omega = 2.0 * kPi * f;
    const int settle = 2 * 4096, fitted = static_cast<int>(std::lround(std::ceil(2.0 * f) / f * 4096.0));
    const LoopResult loop = run_loop([&](double t) { return 1e-3 * std::sin(omega * t); }, settle + fitted);
    std::vector<double> phase(loop.time_s.begin() + settle, loop.time_s.end());
    for (double& p : phase) p *= omega;
    const HarmonicFit fit =
        fit_harmonic(phase, std::vector<double>(loop.displacement_m.begin() + settle, loop.displacement_m.end()));
    const double ratio = fit.amplitude / 1e-3;

    // The reference: the continuous loop with the zero-order hold's lag of T/2 (to first
    // order in w T) inside the loop, L(s) = G_C(s) G(s) e^{-s T/2}. There is no further
    // latency: u_k acts at once on the x_k just measured. The lag must sit inside the loop,
    // not be taken off the closed loop's phase: near 20 Hz the loop is lightly damped and
    // T/2 alone moves |X/R| by 1.4 %, which no phase correction of T(s) can account for.
    const Complex s(0.0, omega);
    const Complex open = continuous_controller(kBenchmarkPi, s) * benchmark_plant_at(s);
    const Complex held = open * std::exp(-s * (kPeriod / 2.0));
    const Complex closed = held / (1.0 + held);
    EXPECT_NEAR(ratio / std::abs(closed), 1.0, 0.01)
        << f << " Hz: discrete " << ratio << ", continuous " << std::abs(closed);
    EXPECT_NEAR(std::remainder(fit.phase_rad - std::arg(closed), 2.0 * kPi) * 180.0 / kPi, 0.0, 1.5)
        << f << " Hz: discrete " << fit.phase_rad * 180.0 / kPi << " deg, continuous " << std::arg(closed) * 180.0 / kPi
        << " deg";
  }
}

TEST(PidController, ClosedLoopDcGainIsOneDespiteThePlantGain) {
  ASSERT_GT(std::abs(benchmark_plant().static_gain() - 1.0), 5e-3);  // G(0) = 1.0075
  const LoopResult loop = run_loop([](double) { return 1e-3; }, 3 * 4096);
  EXPECT_NEAR(loop.displacement_m.back() / 1e-3, 1.0, 1e-4);
}

// The limit bounds the whole output, derivative kick included: a step of 0.5 under Kp = 1
// and a derivative kick of about 45 sits at +1 until the kick has decayed below 0.5.
TEST(PidController, LimitBoundsTheWholeOutputIncludingTheDerivative) {
  const double kd = 0.1, tf = 0.001;
  PidController pid({1.0, 0.0, kd, tf}, kPeriod);
  const double d0 = 2.0 * kd / (2.0 * tf + kPeriod) * 0.5, pole = (2.0 * tf - kPeriod) / (2.0 * tf + kPeriod);
  int limited_samples = 0;
  for (int k = 0; k < 200; ++k) {
    const double unlimited = 0.5 + d0 * std::pow(pole, k);
    const double u = pid.update(0.5, -1.0, 1.0);
    ASSERT_NEAR(u, std::min(unlimited, 1.0), 1e-12) << k;
    ASSERT_EQ(pid.saturated(), unlimited > 1.0) << k;
    limited_samples += pid.saturated();
  }
  EXPECT_GT(limited_samples, 10);
}

// Limits +/-1, error +2 for half a second, then -0.5: the clamped integral stops where the
// limit took over and the output leaves the limit at once; an integral that kept running
// would hold the output at the limit for seconds.
TEST(PidController, ClampingReleasesTheLimitSoonAfterTheErrorReverses) {
  const PidGains gains{0.2, 50.0, 0.0, 0.0};
  PidController pid(gains, kPeriod);
  const int reverse_at = 2048;
  auto error_at = [&](int k) { return k < reverse_at ? 2.0 : -0.5; };
  double unclamped_integral = 0.0, previous_error = 0.0, previous_integral = 0.0;
  int clamped_release = -1, unclamped_release = -1;
  for (int k = 0; k < 6 * 4096; ++k) {
    const double e = error_at(k);
    const double u = pid.update(e, -1.0, 1.0);
    unclamped_integral += gains.integral_per_s * kPeriod / 2.0 * (e + previous_error);
    previous_error = e;
    const double unclamped_u = std::clamp(gains.proportional * e + unclamped_integral, -1.0, 1.0);
    ASSERT_EQ(pid.saturated(), std::abs(u) == 1.0) << k;
    if (k < reverse_at && pid.saturated()) {
      ASSERT_EQ(u, 1.0) << k;
      ASSERT_LE(pid.integral(), previous_integral) << k;  // never grows while pushing the limit
    }
    if (k >= reverse_at && clamped_release < 0 && u < 1.0) clamped_release = k - reverse_at;
    if (k >= reverse_at && unclamped_release < 0 && unclamped_u < 1.0) unclamped_release = k - reverse_at;
    previous_integral = pid.integral();
  }
  ASSERT_GE(clamped_release, 0);
  ASSERT_GE(unclamped_release, 0);
  EXPECT_LE(clamped_release, 3);
  EXPECT_GT(unclamped_release, 1000);
}

TEST(PidController, ResetHoldsTheOutputExactly) {
  PidController pid({1.3, 40.0, 0.02, 0.003}, kPeriod);
  for (int k = 0; k < 100; ++k) pid.update(std::sin(0.1 * k), -5.0, 5.0);
  for (double held : {0.0123456789, -3.75, 0.0}) {
    pid.reset(held);
    EXPECT_FALSE(pid.saturated());
    EXPECT_EQ(pid.update(0.0, -5.0, 5.0), held);
    EXPECT_EQ(pid.update(0.0, -5.0, 5.0), held);
  }
}

TEST(PidController, NonFiniteErrorGivesNanAndBadGainsAreNamed) {
  PidController pid({1.0, 10.0, 0.0, 0.0}, kPeriod);
  EXPECT_TRUE(std::isnan(pid.update(std::numeric_limits<double>::quiet_NaN(), -1.0, 1.0)));
  EXPECT_TRUE(std::isnan(pid.update(0.1, -1.0, 1.0)));  // the state is lost until reset
  pid.reset(0.0);
  EXPECT_EQ(pid.update(0.1, -1.0, 1.0), 0.1 + 10.0 * kPeriod / 2.0 * 0.1);
  EXPECT_FALSE(std::isfinite(pid.update(kInf, -1.0, 1.0)));
  // With every gain finite and nonzero an infinite error would otherwise be limited to +/-1.
  PidController all_terms({1.0, 10.0, 0.01, 0.001}, kPeriod);
  EXPECT_FALSE(std::isfinite(all_terms.update(kInf, -1.0, 1.0)));
  EXPECT_FALSE(std::isfinite(all_terms.update(0.0, -1.0, 1.0)));
  all_terms.reset(0.0);
  EXPECT_FALSE(std::isfinite(all_terms.update(-kInf, -1.0, 1.0)));
  all_terms.reset(0.0);
  EXPECT_TRUE(std::isnan(all_terms.update(0.0, 1.0, -1.0)));  // limits out of order

  auto expect_names = [](const PidGains& gains, const std::string& key) {
    try {
      gains.validate();
      ADD_FAILURE() << "accepted, expected a complaint about " << key;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_names({-1.0, 0.0, 0.0, 0.0}, "proportional");
  expect_names({1.0, nan, 0.0, 0.0}, "integral_per_s");
  expect_names({1.0, 0.0, kInf, 0.001}, "derivative_s");
  expect_names({1.0, 0.0, 0.0, -0.001}, "derivative_filter_time_s");
  expect_names({1.0, 0.0, 0.01, 0.0}, "derivative_filter_time_s");
  expect_names({0.0, 0.0, 0.0, 0.0}, "proportional");
  EXPECT_NO_THROW(PidGains({0.0, 0.0, 0.01, 0.001}).validate());
  EXPECT_THROW(PidController({1.0, 0.0, 0.0, 0.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(PidController({1.0, 0.0, 0.0, 0.0}, nan), std::invalid_argument);
  EXPECT_THROW(PidController({1.0, 0.0, 0.01, 0.4 * kPeriod}, kPeriod), std::invalid_argument);
  EXPECT_NO_THROW(PidController({1.0, 0.0, 0.01, 0.5 * kPeriod}, kPeriod));
}

TEST(PidController, UpdateAllocatesNothing) {
  PidController pid({1.3, 40.0, 0.02, 0.003}, kPeriod);
  double sum = 0.0;
  rpsd::testing::begin_counting_allocations();
  for (int k = 0; k < 10000; ++k) sum += pid.update(std::sin(0.01 * k), -0.5, 0.5);
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace rpsd::servo
