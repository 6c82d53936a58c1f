#include "rpsd/compensation/inverse_compensator.h"

#include "validation.h"

namespace rpsd::compensation {

void InverseCompensationParameters::validate() const {
  detail::require_non_negative("inverse compensation: delay_s", delay_s);
}

InverseCompensator::InverseCompensator(const InverseCompensationParameters& parameters) : parameters_(parameters) {
  parameters_.validate();
}

void InverseCompensator::configure(double dt_s) {
  detail::require_positive("inverse compensation: dt_s", dt_s);
  alpha_ = 1.0 + parameters_.delay_s / dt_s;
  reset(0.0);
}

double InverseCompensator::command(double target_m) noexcept {
  const double u = alpha_ * target_m - (alpha_ - 1.0) * previous_target_m_;
  previous_target_m_ = target_m;
  return u;
}

InverseCompensationParameters InverseCompensationParameters::read(config::Source& section) {
  InverseCompensationParameters p;
  p.delay_s = section.number("delay_s", config::Number::between(0.0, 1.0, "s", "the lag to compensate"));
  return p;
}

}  // namespace rpsd::compensation
