#include "rpsd/compensation/adaptive_time_series_compensator.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "validation.h"

namespace rpsd::compensation {

namespace {
constexpr double kRidge = 1e-9;  // relative to the unit diagonal of the scaled normal matrix
constexpr int kMinWindowSamples = 8;
const char* const kCoefficientNames[3] = {"a0", "a1", "a2"};
}  // namespace

void AdaptiveTimeSeriesParameters::validate() const {
  const std::string w = "adaptive time series: ";
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string c = kCoefficientNames[i];
    detail::require_finite(w + "lower bound of " + c, lower_bounds[i]);
    detail::require_finite(w + "upper bound of " + c, upper_bounds[i]);
    if (!(upper_bounds[i] >= lower_bounds[i])) {
      detail::fail(w + "upper bound of " + c, "must be >= its lower bound " + std::to_string(lower_bounds[i]),
                   upper_bounds[i]);
    }
    detail::require_finite(w + "initial " + c, initial_coefficients[i]);
    if (!(initial_coefficients[i] >= lower_bounds[i] && initial_coefficients[i] <= upper_bounds[i])) {
      detail::fail(w + "initial " + c,
                   "must lie within its bounds [" + std::to_string(lower_bounds[i]) + ", " +
                       std::to_string(upper_bounds[i]) + "]",
                   initial_coefficients[i]);
    }
    detail::require_positive(w + "max rate of " + c + " per second", max_rate_per_s[i]);
  }
  if (!(lower_bounds[0] > 0.0)) {
    detail::fail(w + "lower bound of a0", "must be positive (a0 is the static gain of the command)", lower_bounds[0]);
  }
  detail::require_positive(w + "window_s", window_s);
  if (skip_samples < 1) detail::fail(w + "skip_samples", "must be >= 1", skip_samples);
  detail::require_non_negative(w + "trigger_threshold_m", trigger_threshold_m);
}

AdaptiveTimeSeriesCompensator::AdaptiveTimeSeriesCompensator(const AdaptiveTimeSeriesParameters& parameters)
    : parameters_(parameters) {
  parameters_.validate();
}

void AdaptiveTimeSeriesCompensator::configure(double dt_s) {
  detail::require_positive("adaptive time series: dt_s", dt_s);
  const double samples = std::round(parameters_.window_s / dt_s);
  if (!(samples >= kMinWindowSamples) || samples > 1e8) {
    detail::fail("adaptive time series: window_s / dt_s (samples in the least-squares window)",
                 "must be between 8 and 1e8", samples);
  }
  dt_s_ = dt_s;
  window_samples_ = static_cast<int>(samples);
  capacity_ = window_samples_ + 2;  // two more for the second difference at the window's start
  measured_m_.assign(static_cast<std::size_t>(capacity_), 0.0);
  command_m_.assign(static_cast<std::size_t>(capacity_), 0.0);
  reset(0.0);
}

void AdaptiveTimeSeriesCompensator::reset(double initial_displacement_m) noexcept {
  std::fill(measured_m_.begin(), measured_m_.end(), initial_displacement_m);
  std::fill(command_m_.begin(), command_m_.end(), initial_displacement_m);
  observed_ = 0;
  accepted_updates_ = 0;
  untriggered_updates_ = 0;
  coefficients_ = parameters_.initial_coefficients;
  ramp_from_ = coefficients_;
  goal_ = coefficients_;
  ramp_step_ = parameters_.skip_samples;
  previous_target_m_ = initial_displacement_m;
  before_previous_target_m_ = initial_displacement_m;
  last_command_m_ = initial_displacement_m;
}

double AdaptiveTimeSeriesCompensator::command(double target_m) noexcept {
  const double velocity = (target_m - previous_target_m_) / dt_s_;
  const double acceleration = (target_m - 2.0 * previous_target_m_ + before_previous_target_m_) / (dt_s_ * dt_s_);
  before_previous_target_m_ = previous_target_m_;
  previous_target_m_ = target_m;
  last_command_m_ = coefficients_[0] * target_m + coefficients_[1] * velocity + coefficients_[2] * acceleration;
  return last_command_m_;
}

void AdaptiveTimeSeriesCompensator::observe(double, double measured_m) noexcept {
  assert(!measured_m_.empty() && "configure() first");
  const auto slot = static_cast<std::size_t>(observed_ % capacity_);
  measured_m_[slot] = measured_m;
  command_m_[slot] = last_command_m_;
  ++observed_;
  // Apply the latest update gradually, a straight line over the skip interval: a coefficient
  // that jumps would put a kink into the command, which a second difference of the measurement
  // turns into a spike that then dominates the next windows' D^2 x_m column.
  if (ramp_step_ < parameters_.skip_samples) {
    ++ramp_step_;
    const double fraction = static_cast<double>(ramp_step_) / parameters_.skip_samples;
    for (std::size_t i = 0; i < 3; ++i) {
      coefficients_[i] = std::clamp(ramp_from_[i] + fraction * (goal_[i] - ramp_from_[i]), parameters_.lower_bounds[i],
                                    parameters_.upper_bounds[i]);
    }
  }
  // First update as soon as the window (and the two samples before it) is full, then every
  // skip_samples steps.
  if (observed_ >= capacity_ && (observed_ - capacity_) % parameters_.skip_samples == 0) update_coefficients();
}

void AdaptiveTimeSeriesCompensator::update_coefficients() noexcept {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  double lowest = measured_at(observed_ - 1);
  double highest = lowest;
  const double inv_dt = 1.0 / dt_s_;
  for (long k = observed_ - window_samples_; k < observed_; ++k) {
    const double x0 = measured_at(k);
    const double x1 = measured_at(k - 1);
    const double x2 = measured_at(k - 2);
    const Eigen::Vector3d phi(x0, (x0 - x1) * inv_dt, (x0 - 2.0 * x1 + x2) * inv_dt * inv_dt);
    normal.noalias() += phi * phi.transpose();
    rhs.noalias() += phi * command_at(k);
    lowest = std::min(lowest, x0);
    highest = std::max(highest, x0);
  }
  if (highest - lowest < parameters_.trigger_threshold_m) {
    ++untriggered_updates_;
    return;
  }
  const Eigen::Vector3d scale = normal.diagonal().cwiseSqrt();
  if (!(scale.minCoeff() > 0.0) || !scale.allFinite()) return;
  const Eigen::Vector3d current(coefficients_[0], coefficients_[1], coefficients_[2]);
  Eigen::Matrix3d scaled = normal.array() / (scale * scale.transpose()).array();
  scaled.diagonal().array() += kRidge;
  const Eigen::LLT<Eigen::Matrix3d> llt(scaled);
  if (llt.info() != Eigen::Success) return;
  const Eigen::Vector3d solution =
      llt.solve(rhs.cwiseQuotient(scale) + kRidge * current.cwiseProduct(scale)).cwiseQuotient(scale);
  if (!solution.allFinite()) return;
  // The previous ramp has just ended (updates are skip_samples apart), so coefficients_ is its
  // goal. The new goal is within max_rate * skip * dt of it and within the bounds.
  const double interval_s = parameters_.skip_samples * dt_s_;
  ramp_from_ = coefficients_;
  for (int i = 0; i < 3; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double max_step = parameters_.max_rate_per_s[u] * interval_s;
    const double stepped = coefficients_[u] + std::clamp(solution[i] - coefficients_[u], -max_step, max_step);
    goal_[u] = std::clamp(stepped, parameters_.lower_bounds[u], parameters_.upper_bounds[u]);
  }
  ramp_step_ = 0;
  ++accepted_updates_;
}

}  // namespace rpsd::compensation
