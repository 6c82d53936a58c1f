#include "rpsd/compensation/phase_lead.h"

#include <cmath>
#include <stdexcept>

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

}  // namespace rpsd::compensation
