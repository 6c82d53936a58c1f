// The tracking indicator against its closed forms: pi X^2 sin(w tau) per cycle continuously,
// 1/2 X^2 sin(w tau) sin(w dt) per step exactly when sampled.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rpsd/compensation/tracking_indicator.h"

namespace rpsd::compensation {
namespace {

// TI per cycle over about `cycles` cycles of d_c = X sin(w t), d_m = X sin(w (t - tau)) at
// step dt: TI after a whole number of steps divided by the cycles those steps cover.
double ti_per_cycle(double X, double f_hz, double tau_s, double dt_s, int cycles) {
  const double w = 2.0 * std::numbers::pi * f_hz;
  const long steps = std::lround(cycles / (f_hz * dt_s));
  TrackingIndicator ti;
  for (long n = 0; n <= steps; ++n) {
    const double t = static_cast<double>(n) * dt_s;
    ti.update(X * std::sin(w * t), X * std::sin(w * (t - tau_s)));
  }
  return ti.value_m2() / (static_cast<double>(steps) * f_hz * dt_s);
}

TEST(TrackingIndicator, GrowsByPiXSquaredSinWTauPerCycle) {
  const double X = 0.0125, f = 1.58, dt = 1e-5;
  for (double tau : {0.002, 0.01, 0.081}) {
    const double per_cycle = ti_per_cycle(X, f, tau, dt, 5);
    const double expected = std::numbers::pi * X * X * std::sin(2.0 * std::numbers::pi * f * tau);
    // Sampling shrinks it by sin(w dt) / (w dt) = 1 - 1.6e-9 here.
    EXPECT_NEAR(per_cycle, expected, 1e-8 * expected) << "tau " << tau;
    EXPECT_GT(per_cycle, 0.0);
  }
}

TEST(TrackingIndicator, IsNegativeForALead) {
  const double X = 0.01, f = 2.0, dt = 1e-5, tau = -0.015;
  const double per_cycle = ti_per_cycle(X, f, tau, dt, 3);
  const double expected = std::numbers::pi * X * X * std::sin(2.0 * std::numbers::pi * f * tau);
  EXPECT_LT(per_cycle, 0.0);
  EXPECT_NEAR(per_cycle, expected, 1e-8 * std::abs(expected));
}

TEST(TrackingIndicator, SampledIncrementIsExactlyHalfXSquaredSinWTauSinWDt) {
  // TI+ - TI = 1/2 (d_c d_m+ - d_c+ d_m); for the two sinusoids that is constant.
  const double X = 0.02, w = 2.0 * std::numbers::pi * 3.0, tau = 0.02, dt = 1.0 / 512.0;
  TrackingIndicator ti;
  ti.update(0.0, X * std::sin(-w * tau));
  for (int n = 1; n <= 1000; ++n) {
    const double before = ti.value_m2();
    ti.update(X * std::sin(w * n * dt), X * std::sin(w * (n * dt - tau)));
    ASSERT_NEAR(ti.value_m2() - before, 0.5 * X * X * std::sin(w * tau) * std::sin(w * dt), 1e-18) << n;
  }
}

TEST(TrackingIndicator, IdenticalSignalsGiveZero) {
  TrackingIndicator ti;
  for (int n = 0; n < 1000; ++n) {
    const double x = std::sin(0.01 * n) + 0.3 * std::cos(0.037 * n);
    ti.update(x, x);
  }
  EXPECT_EQ(ti.value_m2(), 0.0);
  EXPECT_EQ(ti.area_a_m2(), ti.area_ta_m2());
}

TEST(TrackingIndicator, OfflineMatchesOnline) {
  std::vector<double> c(500), m(500), history(500);
  TrackingIndicator online;
  for (std::size_t k = 0; k < c.size(); ++k) {
    c[k] = std::sin(0.02 * static_cast<double>(k));
    m[k] = 0.9 * std::sin(0.02 * static_cast<double>(k) - 0.1);
    online.update(c[k], m[k]);
  }
  EXPECT_EQ(tracking_indicator(c, m), online.value_m2());
  tracking_indicator_history(c, m, history);
  EXPECT_EQ(history.front(), 0.0);
  EXPECT_EQ(history.back(), online.value_m2());
  std::vector<double> short_record(499);
  EXPECT_THROW(tracking_indicator(c, short_record), std::invalid_argument);
}

TEST(TrackingIndicator, ResetWithASampleStartsFromIt) {
  TrackingIndicator a, b;
  a.reset(0.1, 0.2);
  a.update(0.3, 0.25);
  b.update(0.1, 0.2);
  b.update(0.3, 0.25);
  EXPECT_EQ(a.value_m2(), b.value_m2());
  EXPECT_NEAR(a.value_m2(), 0.5 * (0.1 * 0.25 - 0.3 * 0.2), 1e-17);
}

}  // namespace
}  // namespace rpsd::compensation
