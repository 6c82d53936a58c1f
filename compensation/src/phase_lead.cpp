#include "rpsd/compensation/phase_lead.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "validation.h"

namespace rpsd::compensation {

void PhaseLeadParameters::validate() const {
  if (!(ratio_a >= 1.0) || !std::isfinite(ratio_a)) throw std::invalid_argument("phase lead: ratio a must be >= 1");
  if (!(time_constant_s >= 0.0) || !std::isfinite(time_constant_s)) {
    throw std::invalid_argument("phase lead: time constant T must be >= 0");
  }
}

double PhaseLeadParameters::max_phase_lead_rad() const { return std::asin((ratio_a - 1.0) / (ratio_a + 1.0)); }

double PhaseLeadParameters::max_lead_frequency_rad_s() const { return 1.0 / (time_constant_s * std::sqrt(ratio_a)); }

PhaseLeadParameters cancel_first_order_lag(double lag_time_constant_s, double ratio_a) {
  PhaseLeadParameters lead{ratio_a, lag_time_constant_s / ratio_a};
  lead.validate();
  return lead;
}

std::complex<double> phase_lead_response(const PhaseLeadParameters& lead, double omega_rad_s) {
  const std::complex<double> s(0.0, omega_rad_s);
  return (1.0 + lead.ratio_a * lead.time_constant_s * s) / (1.0 + lead.time_constant_s * s);
}

PhaseLeadParameters phase_lead_for_delay(double delay_s, double ratio_a) {
  detail::require_non_negative("phase lead design: delay_s", delay_s);
  if (delay_s == 0.0) return PhaseLeadParameters{1.0, 0.0};
  if (!(ratio_a > 1.0) || !std::isfinite(ratio_a)) {
    detail::fail("phase lead design: ratio a", "must be > 1 to supply a lead", ratio_a);
  }
  return PhaseLeadParameters{ratio_a, delay_s / (ratio_a - 1.0)};
}

PhaseLeadParameters phase_lead_for_delay_with_time_constant(double delay_s, double time_constant_s) {
  detail::require_non_negative("phase lead design: delay_s", delay_s);
  detail::require_positive("phase lead design: time constant T", time_constant_s);
  return PhaseLeadParameters{1.0 + delay_s / time_constant_s, time_constant_s};
}

PhaseLeadParameters phase_lead_peaking_at(double delay_s, double frequency_hz) {
  detail::require_non_negative("phase lead design: delay_s", delay_s);
  detail::require_positive("phase lead design: frequency_hz", frequency_hz);
  const double omega = 2.0 * std::numbers::pi * frequency_hz;
  const double phi = omega * delay_s;
  if (!(phi < 0.5 * std::numbers::pi)) {
    detail::fail("phase lead design: 2 pi frequency_hz delay_s (the lead to supply, rad)",
                 "must be below pi/2, the limit of one first-order network", phi);
  }
  if (phi == 0.0) return PhaseLeadParameters{1.0, 0.0};
  const double a = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
  return PhaseLeadParameters{a, 1.0 / (omega * std::sqrt(a))};
}

}  // namespace rpsd::compensation
