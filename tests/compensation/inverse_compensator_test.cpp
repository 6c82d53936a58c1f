// Inverse compensation (Chen & Ricles): with the actuator model G_a(z) = 1/(alpha z - (alpha-1))
// the compensated loop is exactly a one-step delay; the adaptive version finds alpha.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "rpsd/compensation/adaptive_inverse_compensator.h"
#include "rpsd/compensation/inverse_compensator.h"
#include "rpsd/compensation/polynomial_extrapolation.h"
#include "test_signals.h"
#include "test_time_step.h"

namespace rpsd::compensation {
namespace {

// The actuator model of Chen & Ricles: alpha x_m[k+1] - (alpha - 1) x_m[k] = u[k].
struct ChenRiclesActuator {
  double alpha;
  double x = 0.0;
  double step(double u) {
    x = ((alpha - 1.0) * x + u) / alpha;
    return x;
  }
};

TEST(InverseCompensator, CompensatedModelLoopIsExactlyOneStepDelay) {
  for (double alpha : {1.0, 2.5, 13.0}) {
    InverseCompensator c({(alpha - 1.0) * kDt});
    c.configure(kDt);
    EXPECT_NEAR(c.alpha(), alpha, 1e-12);
    c.reset(0.0);
    ChenRiclesActuator actuator{alpha};
    // An arbitrary target: x_m[k+1] must equal x_d[k] at every step, from rest.
    for (int k = 0; k < 2000; ++k) {
      const double target =
          0.01 * std::sin(0.013 * k) + 0.004 * std::cos(0.31 * k * k * 1e-3) + (k > 700 ? 0.002 : 0.0);
      const double measured_next = actuator.step(c.command(target));
      ASSERT_NEAR(measured_next, target, 1e-15) << "alpha " << alpha << " step " << k;
    }
    // And in the z domain: G_c(z) G_a(z) = 1/z on the unit circle.
    for (double theta : {0.01, 0.7, 2.9}) {
      const std::complex<double> z = std::polar(1.0, theta);
      const auto gc = (alpha * z - (alpha - 1.0)) / z;
      const auto ga = 1.0 / (alpha * z - (alpha - 1.0));
      EXPECT_NEAR(std::abs(gc * ga - 1.0 / z), 0.0, 1e-14);
      EXPECT_NEAR(std::abs(testing::simulated_response(c, theta, 10) - gc), 0.0, 1e-12);
    }
  }
}

TEST(InverseCompensator, IsLinearExtrapolationByTheDelay) {
  // x_c = x_d + (alpha - 1)(x_d[k] - x_d[k-1]): Horiuchi's order-1 law with the same delay.
  InverseCompensator inverse({0.0234});
  PolynomialExtrapolationCompensator linear({1, 0.0234});
  inverse.configure(kDt);
  linear.configure(kDt);
  for (int k = 0; k < 200; ++k) {
    const double x = std::sin(0.05 * k);
    EXPECT_NEAR(inverse.command(x), linear.command(x), 1e-13);
  }
}

TEST(InverseCompensator, RejectsNegativeDelay) {
  try {
    InverseCompensator c({-0.001});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("delay_s"), std::string::npos) << e.what();
  }
}

// Runs the adaptive compensator against the model actuator on X sin(w t); returns the
// compensator after `seconds`, and the largest delay change seen in one step.
struct AdaptiveRun {
  double final_delay_s;
  double largest_step_s;
  double lowest_s, highest_s;
  double ti_growth_last_cycle_m2;
  double final_ti_m2;
  double peak_ti_m2;
};

AdaptiveRun run_adaptive(const AdaptiveInverseCompensationParameters& p, double true_alpha, double seconds) {
  AdaptiveInverseCompensator c(p);
  c.configure(kDt);
  c.reset(0.0);
  ChenRiclesActuator actuator{true_alpha};
  const double X = 0.01, w = 2.0 * std::numbers::pi * 1.0;
  const int steps = static_cast<int>(seconds / kDt);
  const int cycle = 1024;
  AdaptiveRun r{0.0, 0.0, 1e9, -1e9, 0.0, 0.0, 0.0};
  double previous = c.compensated_delay_s();
  double ti_cycle_start = 0.0;
  for (int n = 0; n < steps; ++n) {
    const double target = X * std::sin(w * n * kDt);
    const double measured = actuator.step(c.command(target));
    c.observe(target, measured);
    const double d = c.compensated_delay_s();
    r.largest_step_s = std::max(r.largest_step_s, std::abs(d - previous));
    r.lowest_s = std::min(r.lowest_s, d);
    r.highest_s = std::max(r.highest_s, d);
    previous = d;
    r.peak_ti_m2 = std::max(r.peak_ti_m2, std::abs(c.tracking_indicator().value_m2()));
    if (n == steps - cycle) ti_cycle_start = c.tracking_indicator().value_m2();
  }
  r.final_delay_s = c.compensated_delay_s();
  r.ti_growth_last_cycle_m2 = c.tracking_indicator().value_m2() - ti_cycle_start;
  r.final_ti_m2 = c.tracking_indicator().value_m2();
  return r;
}

TEST(AdaptiveInverseCompensator, ConvergesToTheActuatorsAlpha) {
  // True alpha 31: a lag of 30 steps (29.3 ms) in this module's pairing. Starting from no
  // compensation, TI grows while the measurement lags and drives tau up until the loop is
  // exact (G_c G_a = 1/z), where TI stops growing.
  const double true_alpha = 31.0;
  const double true_delay = (true_alpha - 1.0) * kDt;
  AdaptiveInverseCompensationParameters p;
  p.initial_delay_s = 0.0;
  p.max_delay_s = 0.1;
  p.max_delay_rate = 0.05;
  p.proportional_gain_s_per_m2 = 500.0;  // about 1/s convergence at X = 10 mm, 1 Hz
  const AdaptiveRun r = run_adaptive(p, true_alpha, 20.0);
  testing::record("final_delay_s", r.final_delay_s);
  testing::record("true_delay_s", true_delay);
  EXPECT_NEAR(r.final_delay_s, true_delay, 0.005 * true_delay);
  // TI growth per cycle ~ pi X^2 sin(w residual): near zero at the end.
  EXPECT_LT(std::abs(r.ti_growth_last_cycle_m2), 3.14e-4 * std::sin(2.0 * std::numbers::pi * 0.005 * true_delay));
  EXPECT_LE(r.largest_step_s, p.max_delay_rate * kDt * (1.0 + 1e-9));
}

TEST(AdaptiveInverseCompensator, WithIntegralGainConvergesAndReturnsTiTowardsZero) {
  const double true_alpha = 21.0;
  AdaptiveInverseCompensationParameters p;
  p.proportional_gain_s_per_m2 = 500.0;
  p.integral_gain_per_m2 = 100.0;
  const AdaptiveRun r = run_adaptive(p, true_alpha, 30.0);
  EXPECT_NEAR(r.final_delay_s, (true_alpha - 1.0) * kDt, 0.01 * (true_alpha - 1.0) * kDt);
  // With k_i > 0 the equilibrium also needs TI = 0 (else its integral keeps moving tau):
  // TI rises while the lag is being removed, then returns towards zero.
  testing::record("peak_ti_m2", r.peak_ti_m2);
  testing::record("final_ti_m2", r.final_ti_m2);
  EXPECT_LT(std::abs(r.final_ti_m2), 0.02 * r.peak_ti_m2);
}

TEST(AdaptiveInverseCompensator, BoundsAndRateLimitHold) {
  AdaptiveInverseCompensationParameters p;
  p.initial_delay_s = 0.005;
  p.min_delay_s = 0.002;
  p.max_delay_s = 0.015;  // below the true 29.3 ms
  p.max_delay_rate = 0.01;
  p.proportional_gain_s_per_m2 = 5000.0;
  p.integral_gain_per_m2 = 1000.0;
  const AdaptiveRun r = run_adaptive(p, 31.0, 10.0);
  EXPECT_LE(r.highest_s, p.max_delay_s);
  EXPECT_GE(r.lowest_s, p.min_delay_s);
  EXPECT_EQ(r.final_delay_s, p.max_delay_s);
  EXPECT_LE(r.largest_step_s, p.max_delay_rate * kDt * (1.0 + 1e-9));
}

TEST(AdaptiveInverseCompensator, ValidationNamesTheField) {
  AdaptiveInverseCompensationParameters p;
  p.initial_delay_s = 0.2;
  p.max_delay_s = 0.1;
  try {
    AdaptiveInverseCompensator c(p);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("initial_delay_s"), std::string::npos) << e.what();
  }
  p = {};
  p.max_delay_rate = 0.0;
  EXPECT_THROW(AdaptiveInverseCompensator{p}, std::invalid_argument);
  p = {};
  p.proportional_gain_s_per_m2 = -1.0;
  EXPECT_THROW(AdaptiveInverseCompensator{p}, std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
