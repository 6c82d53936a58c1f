// The discrete phase lead against the exact closed form of its bilinear discretisation and
// against the continuous network at low w dt.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rpsd/compensation/discrete_phase_lead.h"
#include "test_signals.h"
#include "test_time_step.h"

namespace rpsd::compensation {
namespace {

TEST(DiscretePhaseLead, SimulatedResponseEqualsTheBilinearMapOfTheContinuousNetwork) {
  // H(e^{j w dt}) = G_c(j (2/dt) tan(w dt / 2)) at every frequency up to near Nyquist.
  const auto p = DiscretePhaseLeadParameters::for_delay(0.08, 5.0);  // T = 20 ms
  DiscretePhaseLeadCompensator c(p);
  c.configure(kDt);
  for (double theta : {0.001, 0.01, 0.1, 0.5, 1.0, 2.0, 3.0}) {
    const std::complex<double> measured = testing::simulated_response(c, theta, 4000);
    const std::complex<double> exact = phase_lead_response(p.network, 2.0 / kDt * std::tan(theta / 2.0));
    EXPECT_NEAR(std::abs(measured - exact), 0.0, 1e-11 * std::abs(exact)) << "w dt = " << theta;
    EXPECT_NEAR(std::abs(discrete_phase_lead_response(p, kDt, theta / kDt) - exact), 0.0, 1e-14);
  }
}

TEST(DiscretePhaseLead, AgreesWithTheContinuousNetworkAtLowFrequency) {
  // |H - G_c(j w)| <= sup|G_c'| |K tan(w dt/2) - w| <= (a - 1) T w (w dt)^2 / 12 (1 + O(w dt)^2).
  const auto p = DiscretePhaseLeadParameters::for_delay(0.08, 5.0);
  DiscretePhaseLeadCompensator c(p);
  c.configure(kDt);
  const double lead = p.network.low_frequency_lead_s();
  for (double f : {0.5, 1.58, 2.0, 5.0, 8.0}) {
    const double w = 2.0 * std::numbers::pi * f;
    const std::complex<double> measured = testing::simulated_response(c, w * kDt, 4000);
    const std::complex<double> continuous = phase_lead_response(p.network, w);
    const double bound = lead * w * std::pow(w * kDt, 2) / 12.0 * 1.01;
    EXPECT_LE(std::abs(measured - continuous), bound) << f << " Hz";
    EXPECT_LT(std::abs(measured - continuous), 1e-3) << f << " Hz";
  }
}

TEST(DiscretePhaseLead, KeepsTheLowFrequencyLeadOfTheDesignRule) {
  // phase(w) / w -> (a - 1) T = the delay it was designed for (plain Tustin).
  for (double a : {2.0, 5.0, 10.0}) {
    const auto p = DiscretePhaseLeadParameters::for_delay(0.05, a);
    DiscretePhaseLeadCompensator c(p);
    c.configure(kDt);
    const double w = 2.0 * std::numbers::pi * 0.05;  // far below the pole
    const double phase = std::arg(testing::simulated_response(c, w * kDt, 20000));
    EXPECT_NEAR(phase / w, 0.05, 0.05 * std::pow(w * 0.05 * a, 2)) << "a = " << a;
    EXPECT_NEAR(c.compensated_delay_s(), 0.05, 1e-15);
  }
}

TEST(DiscretePhaseLead, PrewarpedIsExactAtItsFrequency) {
  auto p = DiscretePhaseLeadParameters::for_delay(0.08, 5.0);
  p.prewarp_frequency_hz = 1.58;
  DiscretePhaseLeadCompensator c(p);
  c.configure(kDt);
  const double w = 2.0 * std::numbers::pi * 1.58;
  const std::complex<double> measured = testing::simulated_response(c, w * kDt, 4000);
  EXPECT_NEAR(std::abs(measured - phase_lead_response(p.network, w)), 0.0, 1e-11);
  // Its low-frequency lead is scaled by (w_p dt / 2) / tan(w_p dt / 2).
  EXPECT_NEAR(c.compensated_delay_s(), 0.08 * (w * kDt / 2.0) / std::tan(w * kDt / 2.0), 1e-15);
}

TEST(DiscretePhaseLead, CoefficientsHaveUnitDcGainAndGainAAtNyquist) {
  const auto p = DiscretePhaseLeadParameters::for_delay(0.03, 4.0);
  const FirstOrderSection s = tustin_phase_lead(p, kDt);
  EXPECT_NEAR((s.b0 + s.b1) / (1.0 + s.a1), 1.0, 1e-14);
  EXPECT_NEAR((s.b0 - s.b1) / (1.0 - s.a1), 4.0, 1e-12);  // z = -1 maps to s = infinity
}

TEST(DiscretePhaseLead, HoldsAConstantTargetFromReset) {
  DiscretePhaseLeadCompensator c(DiscretePhaseLeadParameters::for_delay(0.08, 5.0));
  c.configure(kDt);
  c.reset(0.0123);
  for (int n = 0; n < 100; ++n) EXPECT_NEAR(c.command(0.0123), 0.0123, 1e-17);
}

TEST(DiscretePhaseLead, StepResponseStartsAtB0AndSettlesToTheStep) {
  // The bilinear step response: y[0] = b0 = (1 + 2aT/dt) / (1 + 2T/dt), then
  // y[n] = 1 + (b0 - 1) (-a1)^n.
  const auto p = DiscretePhaseLeadParameters{PhaseLeadParameters{5.0, 0.02}, 0.0};
  DiscretePhaseLeadCompensator c(p);
  c.configure(kDt);
  const double b0 = (1.0 + 2.0 * 5.0 * 0.02 / kDt) / (1.0 + 2.0 * 0.02 / kDt);
  const double pole = (2.0 * 0.02 / kDt - 1.0) / (2.0 * 0.02 / kDt + 1.0);
  for (int n = 0; n < 200; ++n) EXPECT_NEAR(c.command(1.0), 1.0 + (b0 - 1.0) * std::pow(pole, n), 1e-12);
}

TEST(DiscretePhaseLead, ZeroDelayIsTheIdentity) {
  DiscretePhaseLeadCompensator c(DiscretePhaseLeadParameters::for_delay(0.0, 5.0));
  c.configure(kDt);
  for (double x : {0.1, -0.3, 0.7}) EXPECT_EQ(c.command(x), x);
  EXPECT_EQ(c.compensated_delay_s(), 0.0);
}

TEST(DiscretePhaseLead, RejectsAPrewarpFrequencyAtOrAboveNyquist) {
  auto p = DiscretePhaseLeadParameters::for_delay(0.05, 5.0);
  p.prewarp_frequency_hz = 512.0;
  DiscretePhaseLeadCompensator c(p);
  try {
    c.configure(kDt);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("prewarp_frequency_hz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("512"), std::string::npos) << e.what();
  }
  EXPECT_THROW(DiscretePhaseLeadCompensator(DiscretePhaseLeadParameters{PhaseLeadParameters{0.5, 0.01}, 0.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
