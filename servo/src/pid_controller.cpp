#include "rpsd/servo/pid_controller.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::servo {
namespace {

void require_gain_non_negative(double value, const char* key) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw std::invalid_argument(std::string(key) + ": must be finite and zero or positive");
  }
}

}  // namespace

void PidGains::validate() const {
  require_gain_non_negative(proportional, "proportional");
  require_gain_non_negative(integral_per_s, "integral_per_s");
  require_gain_non_negative(derivative_s, "derivative_s");
  require_gain_non_negative(derivative_filter_time_s, "derivative_filter_time_s");
  if (derivative_s > 0.0 && derivative_filter_time_s == 0.0) {
    throw std::invalid_argument("derivative_filter_time_s: must be positive when derivative_s is");
  }
  if (proportional == 0.0 && integral_per_s == 0.0 && derivative_s == 0.0) {
    throw std::invalid_argument("proportional, integral_per_s, derivative_s: all zero, no feedback");
  }
}

PidController::PidController(const PidGains& gains, double period_s) : gains_(gains), period_s_(period_s) {
  gains_.validate();
  if (!(std::isfinite(period_s) && period_s > 0.0)) {
    throw std::invalid_argument("period_s: must be finite and positive");
  }
  const double tf = gains_.derivative_filter_time_s;
  if (gains_.derivative_s > 0.0 && tf < 0.5 * period_s) {
    throw std::invalid_argument("derivative_filter_time_s: must be at least period_s / 2 with derivative action");
  }
  integral_step_ = 0.5 * gains_.integral_per_s * period_s;
  derivative_pole_ = (2.0 * tf - period_s) / (2.0 * tf + period_s);
  derivative_gain_ = 2.0 * gains_.derivative_s / (2.0 * tf + period_s);
}

double PidController::update(double error, double output_min, double output_max) {
  if (!std::isfinite(error) || !(output_min <= output_max)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    integral_ = derivative_ = previous_error_ = nan;
    saturated_ = false;
    return nan;
  }
  const double increment = integral_step_ * (error + previous_error_);
  derivative_ = derivative_pole_ * derivative_ + derivative_gain_ * (error - previous_error_);
  previous_error_ = error;
  const double unlimited = gains_.proportional * error + integral_ + increment + derivative_;
  const double limited = unlimited > output_max ? output_max : (unlimited < output_min ? output_min : unlimited);
  saturated_ = unlimited > output_max || unlimited < output_min;
  // Clamping rather than back-calculation: it needs no tracking time constant to tune, and
  // the integral stays exactly where it was when the limit took over.
  const bool pushing_further =
      (unlimited > output_max && increment > 0.0) || (unlimited < output_min && increment < 0.0);
  if (!pushing_further) integral_ += increment;
  return limited;
}

void PidController::reset(double held_output) {
  integral_ = held_output;
  derivative_ = 0.0;
  previous_error_ = 0.0;
  saturated_ = false;
}

}  // namespace rpsd::servo
