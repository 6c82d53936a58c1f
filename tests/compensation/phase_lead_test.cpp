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

TEST(PhaseLead, RejectsRatioBelowOne) {
  EXPECT_THROW(cancel_first_order_lag(0.08, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
