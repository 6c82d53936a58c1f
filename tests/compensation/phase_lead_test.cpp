#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rpsd/compensation/phase_lead.h"

namespace rpsd::compensation {
namespace {

TEST(PhaseLead, MaximumLeadAndItsFrequencyMatchClosedForm) {
  const PhaseLeadParameters lead{5.0, 0.01};
  const double omega_m = lead.max_lead_frequency_rad_s();
  EXPECT_NEAR(omega_m, 1.0 / (0.01 * std::sqrt(5.0)), 1e-12);
  EXPECT_NEAR(std::arg(phase_lead_response(lead, omega_m)), std::asin(4.0 / 6.0), 1e-12);
  // It is the maximum: the phase is lower on either side.
  EXPECT_LT(std::arg(phase_lead_response(lead, 0.8 * omega_m)), lead.max_phase_lead_rad());
  EXPECT_LT(std::arg(phase_lead_response(lead, 1.25 * omega_m)), lead.max_phase_lead_rad());
}

TEST(PhaseLead, GainIsOneAtDcAndAAtHighFrequency) {
  const PhaseLeadParameters lead{4.0, 0.02};
  EXPECT_NEAR(std::abs(phase_lead_response(lead, 0.0)), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(phase_lead_response(lead, 1e9)), 4.0, 1e-6);
}

TEST(PhaseLead, CancellingAFirstOrderLagLeavesOnlyTheFastPole) {
  const double lag = 0.0812;
  const PhaseLeadParameters lead = cancel_first_order_lag(lag, 5.0);
  for (double omega : {1.0, 10.0, 60.0}) {
    const std::complex<double> s(0.0, omega);
    const auto compensated = phase_lead_response(lead, omega) / (1.0 + lag * s);
    const auto fast_pole = 1.0 / (1.0 + lead.time_constant_s * s);
    EXPECT_NEAR(std::abs(compensated - fast_pole), 0.0, 1e-12);
  }
  EXPECT_NEAR(lead.low_frequency_lead_s(), lag * 4.0 / 5.0, 1e-15);
}

TEST(PhaseLead, DesignFromADelaySuppliesThatLowFrequencyLead) {
  // (a - 1) T = tau: the phase atan(a T w) - atan(T w) tends to tau w.
  const double tau = 0.081;
  for (const PhaseLeadParameters& lead :
       {phase_lead_for_delay(tau, 5.0), phase_lead_for_delay_with_time_constant(tau, 0.01)}) {
    EXPECT_NEAR(lead.low_frequency_lead_s(), tau, 1e-15);
    const double w = 1e-3;
    EXPECT_NEAR(std::arg(phase_lead_response(lead, w)) / w, tau, 1e-6);
  }
  EXPECT_NEAR(phase_lead_for_delay(tau, 5.0).time_constant_s, tau / 4.0, 1e-15);
  EXPECT_NEAR(phase_lead_for_delay_with_time_constant(tau, 0.01).ratio_a, 9.1, 1e-12);
  EXPECT_EQ(phase_lead_for_delay(0.0, 5.0).time_constant_s, 0.0);
}

TEST(PhaseLead, PeakingDesignSuppliesOmegaTauAtTheDominantFrequency) {
  const double tau = 0.081, f = 1.58;
  const PhaseLeadParameters lead = phase_lead_peaking_at(tau, f);
  const double w = 2.0 * std::numbers::pi * f;
  EXPECT_NEAR(lead.max_lead_frequency_rad_s(), w, 1e-9);
  EXPECT_NEAR(std::arg(phase_lead_response(lead, w)), w * tau, 1e-12);
  EXPECT_THROW(phase_lead_peaking_at(0.2, 2.0), std::invalid_argument);  // w tau > pi/2
}

TEST(PhaseLead, RejectsRatioBelowOne) {
  EXPECT_THROW(cancel_first_order_lag(0.08, 0.5), std::invalid_argument);
  EXPECT_THROW(phase_lead_for_delay(0.08, 1.0), std::invalid_argument);
  EXPECT_THROW(phase_lead_for_delay(-0.01, 5.0), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
