#include "rpsd/compensation/adaptive_inverse_compensator.h"

#include <algorithm>

#include "validation.h"

namespace rpsd::compensation {

void AdaptiveInverseCompensationParameters::validate() const {
  const std::string w = "adaptive inverse compensation: ";
  detail::require_non_negative(w + "min_delay_s", min_delay_s);
  detail::require_finite(w + "max_delay_s", max_delay_s);
  if (!(max_delay_s >= min_delay_s)) {
    detail::fail(w + "max_delay_s", "must be >= min_delay_s = " + detail::number(min_delay_s), max_delay_s);
  }
  detail::require_finite(w + "initial_delay_s", initial_delay_s);
  if (!(initial_delay_s >= min_delay_s && initial_delay_s <= max_delay_s)) {
    detail::fail(w + "initial_delay_s",
                 "must lie in [min_delay_s, max_delay_s] = [" + detail::number(min_delay_s) + ", " +
                     detail::number(max_delay_s) + "]",
                 initial_delay_s);
  }
  detail::require_positive(w + "max_delay_rate", max_delay_rate);
  detail::require_non_negative(w + "proportional_gain_s_per_m2", proportional_gain_s_per_m2);
  detail::require_non_negative(w + "integral_gain_per_m2", integral_gain_per_m2);
}

AdaptiveInverseCompensator::AdaptiveInverseCompensator(const AdaptiveInverseCompensationParameters& parameters)
    : parameters_(parameters) {
  parameters_.validate();
}

void AdaptiveInverseCompensator::configure(double dt_s) {
  detail::require_positive("adaptive inverse compensation: dt_s", dt_s);
  dt_s_ = dt_s;
  reset(0.0);
}

void AdaptiveInverseCompensator::reset(double initial_displacement_m) noexcept {
  delay_s_ = parameters_.initial_delay_s;
  ti_integral_m2_s_ = 0.0;
  previous_target_m_ = initial_displacement_m;
  indicator_.reset(initial_displacement_m, initial_displacement_m);
}

double AdaptiveInverseCompensator::command(double target_m) noexcept {
  const double a = alpha();
  const double u = a * target_m - (a - 1.0) * previous_target_m_;
  previous_target_m_ = target_m;
  return u;
}

void AdaptiveInverseCompensator::observe(double target_m, double measured_m) noexcept {
  indicator_.update(target_m, measured_m);
  const double ti = indicator_.value_m2();
  const bool at_max = delay_s_ >= parameters_.max_delay_s && ti > 0.0;
  const bool at_min = delay_s_ <= parameters_.min_delay_s && ti < 0.0;
  if (!at_max && !at_min) ti_integral_m2_s_ += ti * dt_s_;
  const double law = parameters_.initial_delay_s + parameters_.proportional_gain_s_per_m2 * ti +
                     parameters_.integral_gain_per_m2 * ti_integral_m2_s_;
  const double max_step = parameters_.max_delay_rate * dt_s_;
  delay_s_ = std::clamp(delay_s_ + std::clamp(law - delay_s_, -max_step, max_step), parameters_.min_delay_s,
                        parameters_.max_delay_s);
}

AdaptiveInverseCompensationParameters AdaptiveInverseCompensationParameters::read(config::Source& section) {
  AdaptiveInverseCompensationParameters a;
  // A servo's delay is milliseconds: 1 s bounds every delay; the gains act on m^2.
  using config::Number;
  a.initial_delay_s =
      section.number("initial_delay_s", Number::between(0.0, 1.0, "s", "tau_0, the delay at the start"));
  a.min_delay_s = section.number_or("min_delay_s", a.min_delay_s, Number::between(0.0, 1.0, "s", "tau_min"));
  a.max_delay_s = section.number_or("max_delay_s", a.max_delay_s, {"s", "tau_max", 0.0, 1.0, true});
  a.max_delay_rate = section.number_or("max_delay_rate", a.max_delay_rate,
                                       {"", "seconds of delay the estimate may change per second", 0.0, 10.0, true});
  a.proportional_gain_s_per_m2 = section.number_or("proportional_gain_s_per_m2", a.proportional_gain_s_per_m2,
                                                   Number::between(0.0, 1e9, "s/m^2", "k_p on the tracking indicator"));
  a.integral_gain_per_m2 =
      section.number_or("integral_gain_per_m2", a.integral_gain_per_m2,
                        Number::between(0.0, 1e9, "1/m^2", "k_i on the tracking indicator's integral"));
  return a;
}

}  // namespace rpsd::compensation
