// ATS (Chae, Kazemibidokhti & Ricles 2013) on an ideal delay plant: the identified
// coefficients approach the delay's Taylor coefficients, within bounds and rate limits.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <numbers>

#include "rpsd/compensation/adaptive_time_series_compensator.h"
#include "test_signals.h"
#include "test_time_step.h"

namespace rpsd::compensation {
namespace {

// x_m[n] = u[n - m]: the ideal delay plant in this module's pairing.
struct DelayLine {
  std::deque<double> line;
  explicit DelayLine(int m, double x0 = 0.0) : line(static_cast<std::size_t>(m), x0) {}
  double step(double u) {
    line.push_back(u);
    const double x = line.front();
    line.pop_front();
    return x;
  }
};

// A broadband target (three incommensurate tones, 10 mm overall): x, Dx and D^2x are then
// linearly independent over a 1 s window, so all three coefficients are identifiable.
const testing::MultiSine kTarget{{0.006, 0.003, 0.0015}, {0.7, 1.3, 2.1}, {0.0, 1.0, 2.0}};

struct Trace {
  std::vector<std::array<double, 3>> coefficients;  // after every step
  double worst_late_error_m = 0.0;                  // |x_m - x_t| over the last 2 s
};

Trace run(AdaptiveTimeSeriesCompensator& c, int delay_steps, double seconds, const testing::MultiSine& target) {
  // Start at rest on the target's first value (a jump from 0 would put a spike of
  // a2 D^2 x_t ~ 1 m into the first command).
  DelayLine plant(delay_steps, target(0.0));
  c.reset(target(0.0));
  Trace t;
  const int steps = static_cast<int>(seconds / kDt);
  for (int n = 0; n < steps; ++n) {
    const double x = target(n * kDt);
    const double measured = plant.step(c.command(x));
    c.observe(x, measured);
    t.coefficients.push_back(c.coefficients());
    if (n > steps - 2048) t.worst_late_error_m = std::max(t.worst_late_error_m, std::abs(measured - x));
  }
  return t;
}

TEST(AdaptiveTimeSeries, ConvergesToTheDelayOfAnIdealDelayPlant) {
  // tau = 20 steps = 19.5 ms. With backward differences the delay operator z^m expands as
  // 1 + m dt D + m (m + 1) dt^2 / 2 D^2 + O(D^3): a0 -> 1, a1 -> tau, a2 -> tau (tau + dt) / 2,
  // up to the part of the cubic and higher terms that the least squares folds into the three
  // (relative size (w tau)^3 / 6 = 0.3 % at the 2.1 Hz tone) and the window-to-window
  // variation of that fold: tolerances 0.5 % on a0, 1.5 % on a1, 5 % on a2.
  const int m = 20;
  const double tau = m * kDt;
  AdaptiveTimeSeriesParameters p;
  p.initial_coefficients = {1.0, 0.0, 0.0};  // start with no compensation
  AdaptiveTimeSeriesCompensator c(p);
  c.configure(kDt);
  ASSERT_EQ(c.window_samples(), 1024);
  const Trace t = run(c, m, 12.0, kTarget);
  const auto& a = t.coefficients.back();
  testing::record("a0", a[0]);
  testing::record("a1_s", a[1]);
  testing::record("a2_s2", a[2]);
  testing::record("worst_error_last_2s_m", t.worst_late_error_m);
  EXPECT_NEAR(a[0], 1.0, 0.005);
  EXPECT_NEAR(a[1], tau, 0.015 * tau);
  EXPECT_NEAR(a[2], tau * (tau + kDt) / 2.0, 0.05 * tau * (tau + kDt) / 2.0);
  EXPECT_NEAR(c.compensated_delay_s(), tau, 0.015 * tau);
  EXPECT_GT(c.accepted_updates(), 500);
  // Tracking: uncompensated, the lag would leave errors up to about 0.6 mm.
  EXPECT_LT(t.worst_late_error_m, 1e-5);
}

TEST(AdaptiveTimeSeries, CoefficientsStayInBoundsAndRespectTheRateLimits) {
  // tau = 100 ms is beyond a1's upper bound 0.08 s and a2's 0.0032 s^2: both saturate.
  const int m = 102;
  AdaptiveTimeSeriesParameters p;
  p.initial_coefficients = {1.0, 0.0, 0.0};
  AdaptiveTimeSeriesCompensator c(p);
  c.configure(kDt);
  const Trace t = run(c, m, 10.0, kTarget);
  std::array<double, 3> previous = p.initial_coefficients;
  int changes = 0;
  for (std::size_t n = 0; n < t.coefficients.size(); ++n) {
    const auto& a = t.coefficients[n];
    for (std::size_t i = 0; i < 3; ++i) {
      ASSERT_GE(a[i], p.lower_bounds[i]) << "coefficient " << i << " step " << n;
      ASSERT_LE(a[i], p.upper_bounds[i]) << "coefficient " << i << " step " << n;
      // Each update is ramped in over skip_samples steps: the rate limit holds per step.
      const double limit = p.max_rate_per_s[i] * kDt;
      ASSERT_LE(std::abs(a[i] - previous[i]), limit * (1.0 + 1e-9)) << "coefficient " << i << " step " << n;
      if (a[i] != previous[i]) ++changes;
    }
    previous = a;
  }
  EXPECT_GT(changes, 0);
  ASSERT_EQ(t.coefficients.back()[1], p.upper_bounds[1]);
  // a1 climbs from 0 to 0.08 no faster than 0.05 per second: at least 1.6 s, after the first
  // window has filled.
  std::size_t first_at_bound = 0;
  while (t.coefficients[first_at_bound][1] < p.upper_bounds[1]) ++first_at_bound;
  EXPECT_GE(first_at_bound * kDt, 0.08 / 0.05 + c.window_samples() * kDt);
}

TEST(AdaptiveTimeSeries, BelowTheTriggerThresholdTheCoefficientsHold) {
  AdaptiveTimeSeriesParameters p;
  p.trigger_threshold_m = 0.05;  // the 10 mm target never spans 50 mm
  AdaptiveTimeSeriesCompensator c(p);
  c.configure(kDt);
  const Trace t = run(c, 20, 4.0, kTarget);
  EXPECT_EQ(t.coefficients.back(), p.initial_coefficients);
  EXPECT_EQ(c.accepted_updates(), 0);
  EXPECT_GT(c.untriggered_updates(), 100);
}

TEST(AdaptiveTimeSeries, SingleToneTracksThoughOnlyTwoCoefficientsAreIdentifiable) {
  // One sinusoid spans a rank-2 window; the ridge keeps the third direction where it is and
  // the two identifiable combinations still remove the lag at that frequency.
  const testing::MultiSine tone{{0.01}, {1.5}, {0.0}};
  AdaptiveTimeSeriesParameters p;
  p.initial_coefficients = {1.0, 0.0, 0.0};
  AdaptiveTimeSeriesCompensator c(p);
  c.configure(kDt);
  const Trace t = run(c, 20, 12.0, tone);
  EXPECT_GT(c.accepted_updates(), 500);
  EXPECT_LT(t.worst_late_error_m, 1e-5);  // uncompensated: w tau X = 1.8 mm
}

TEST(AdaptiveTimeSeries, ValidationNamesTheCoefficient) {
  AdaptiveTimeSeriesParameters p;
  p.initial_coefficients[1] = 0.09;
  try {
    AdaptiveTimeSeriesCompensator c(p);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("initial a1"), std::string::npos) << e.what();
  }
  p = {};
  p.skip_samples = 0;
  EXPECT_THROW(AdaptiveTimeSeriesCompensator{p}, std::invalid_argument);
  p = {};
  AdaptiveTimeSeriesCompensator c(p);
  EXPECT_THROW(c.configure(0.5), std::invalid_argument);  // a 1 s window of 2 samples
}

}  // namespace
}  // namespace rpsd::compensation
