// Every compensator through the factory: properties all of them share (rest at reset, unit
// low-frequency gain, name), and the factory's dispatch and validation.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <numbers>
#include <vector>

#include "rpsd/compensation/compensator_factory.h"

namespace rpsd::compensation {
namespace {

constexpr double kFactoryStepS = 1.0 / 2048.0;

std::vector<CompensatorConfig> all_configs() {
  AdaptiveInverseCompensationParameters adaptive_inverse;
  adaptive_inverse.initial_delay_s = 0.01;
  adaptive_inverse.proportional_gain_s_per_m2 = 100.0;
  return {PassThroughParameters{}, DiscretePhaseLeadParameters::for_delay(0.03, 4.0),
          DiscretePhaseLeadParameters::for_delay(0.03, 4.0, 2.0), PolynomialExtrapolationParameters{3, 0.0123},
          InverseCompensationParameters{0.02}, adaptive_inverse, AdaptiveTimeSeriesParameters{},
          // A lag-lead of unit DC gain: (s + 20)(s + 40) / ((s + 10)(s + 80)).
          LtiFilterParameters{{{1.0, 60.0, 800.0}, {1.0, 90.0, 800.0}}, 0.0}};
}

TEST(CompensatorFactory, MakesTheSchemeTheConfigNames) {
  for (const CompensatorConfig& config : all_configs()) {
    const auto c = make_compensator(config, kFactoryStepS);
    EXPECT_EQ(c->name(), compensator_name(config));
  }
  EXPECT_EQ(compensator_name(PassThroughParameters{}), "none");
  EXPECT_EQ(compensator_name(AdaptiveTimeSeriesParameters{}), "adaptive_time_series");
}

TEST(CompensatorFactory, EveryCompensatorHoldsAConstantTargetAfterReset) {
  for (const CompensatorConfig& config : all_configs()) {
    const auto c = make_compensator(config, kFactoryStepS);
    c->reset(0.0254);
    for (int n = 0; n < 3000; ++n) {
      const double u = c->command(0.0254);
      // Rounding only: the order-3 extrapolator at alpha = 25 has coefficients up to ~3000.
      ASSERT_NEAR(u, 0.0254, 1e-12) << c->name() << " step " << n;
      c->observe(0.0254, 0.0254);
    }
  }
}

TEST(CompensatorFactory, EveryCompensatorLeadsASlowRampByItsCompensatedDelay) {
  // On a ramp x_t = v t every scheme here settles to u = x_t + v * (its low-frequency lead):
  // exactly for the linear filters, through a0 = 1 for ATS.
  const double v = 0.01;  // m/s
  for (const CompensatorConfig& config : all_configs()) {
    if (std::holds_alternative<AdaptiveInverseCompensationParameters>(config)) continue;  // adapts
    const auto c = make_compensator(config, kFactoryStepS);
    c->reset(0.0);
    double u = 0.0, x = 0.0;
    for (int n = 0; n < 20000; ++n) {
      x = v * n * kFactoryStepS;
      u = c->command(x);
    }
    const double lead = c->name() == "adaptive_time_series"
                            ? AdaptiveTimeSeriesParameters{}.initial_coefficients[1]  // a1 D x = a1 v
                            : c->compensated_delay_s();
    EXPECT_NEAR(u - x, v * lead, 1e-12) << c->name();
  }
}

TEST(CompensatorFactory, ReportsConfigurationErrorsPrecisely) {
  try {
    make_compensator(PolynomialExtrapolationParameters{7, 0.01}, kFactoryStepS);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "polynomial extrapolation: order: must be 0, 1, 2 or 3, got 7");
  }
  try {
    make_compensator(InverseCompensationParameters{0.01}, -1.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "inverse compensation: dt_s: must be positive and finite, got -1");
  }
  EXPECT_THROW(make_compensator(PassThroughParameters{}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
