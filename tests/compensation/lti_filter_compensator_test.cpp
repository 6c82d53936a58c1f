// The general LTI compensator: the difference equation it runs is its Tustin image (a
// first-order lead against its closed-form impulse response, the seed paper's phase lead
// against the dedicated network sample by sample), it starts at rest at its DC image, and
// an unstable or integrating filter is refused.
#include "rpsd/compensation/lti_filter_compensator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "rpsd/compensation/discrete_phase_lead.h"

namespace rpsd::compensation {
namespace {

constexpr double kFilterStepS = 1.0 / 4096.0;

LtiFilterParameters filter(std::vector<double> n, std::vector<double> d, double prewarp_hz = 0.0) {
  return LtiFilterParameters{{std::move(n), std::move(d)}, prewarp_hz};
}

TEST(LtiFilterCompensator, AFirstOrderLeadRespondsToAnImpulseAsItsBilinearImage) {
  // G = 50.8 (s + 168.6) / (s + 8570): y[0] = b0, then y[n] = (b1 - a1 b0) (-a1)^(n-1).
  LtiFilterCompensator c(filter({50.8, 50.8 * 168.6}, {1.0, 8570.0}));
  c.configure(kFilterStepS);
  const double K = 2.0 / kFilterStepS;
  const double b0 = 50.8 * (K + 168.6) / (K + 8570.0), b1 = 50.8 * (168.6 - K) / (K + 8570.0);
  const double a1 = (8570.0 - K) / (K + 8570.0);
  EXPECT_NEAR(c.command(1.0), b0, 1e-12);
  for (int n = 1; n < 20; ++n) {
    EXPECT_NEAR(c.command(0.0), (b1 - a1 * b0) * std::pow(-a1, n - 1), 1e-12) << n;
  }
}

TEST(LtiFilterCompensator, ThePapersPhaseLeadGivenAsATransferFunctionIsThePhaseLeadNetwork) {
  const DiscretePhaseLeadParameters lead = DiscretePhaseLeadParameters::for_delay(0.03, 4.0, 2.0);
  const double aT = lead.network.ratio_a * lead.network.time_constant_s, T = lead.network.time_constant_s;
  LtiFilterCompensator general(filter({aT, 1.0}, {T, 1.0}, 2.0));
  DiscretePhaseLeadCompensator network(lead);
  general.configure(kFilterStepS);
  network.configure(kFilterStepS);
  general.reset(0.004);
  network.reset(0.004);
  for (int n = 0; n < 4096; ++n) {
    const double x = 0.004 + 0.01 * std::sin(2.0 * 3.14159265358979 * 1.3 * n * kFilterStepS);
    ASSERT_NEAR(general.command(x), network.command(x), 1e-15) << n;
  }
  EXPECT_NEAR(general.compensated_delay_s(), network.compensated_delay_s(), 1e-15);
}

TEST(LtiFilterCompensator, AtRestItHoldsTheDcImageOfItsInput) {
  // A third-order filter with DC gain 0.5: a constant input x gives 0.5 x from the first step.
  LtiFilterCompensator c(filter({0.5 * 6.0e3, 0.5 * 6.0e5}, {1.0, 60.0, 1.1e4, 6.0e5}));
  c.configure(kFilterStepS);
  c.reset(0.02);
  // Rounding: the discrete DC gain is a ratio of coefficient sums ~1e-6 of the coefficients
  // (poles near z = 1), ~1e-11 relative; a wrong rest state is off by O(1).
  for (int n = 0; n < 100; ++n) ASSERT_NEAR(c.command(0.02), 0.01, 1e-11) << n;
}

TEST(LtiFilterCompensator, RefusesAFilterThatIsNotStable) {
  LtiFilterCompensator integrating(filter({1.0}, {1.0, 0.0}));
  EXPECT_THAT([&] { integrating.configure(kFilterStepS); },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("not in the left half-plane")));
  LtiFilterCompensator unstable(filter({1.0}, {1.0, -3.0, 2.0}));
  EXPECT_THAT([&] { unstable.configure(kFilterStepS); },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("pole at s = 2")));
}

}  // namespace
}  // namespace rpsd::compensation
