#include "rpsd/coordinator/experimental_exchange.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {

ExperimentalExchange::ExperimentalExchange(ExchangeParts parts) : parts_(std::move(parts)) {
  if (!parts_.link) throw std::invalid_argument("ExperimentalExchange: a link is required");
  channels_ = static_cast<int>(parts_.compensators.size());
  if (channels_ < 1 || channels_ > transport::kMaxChannels) {
    throw std::invalid_argument("ExperimentalExchange: between 1 and " + std::to_string(transport::kMaxChannels) +
                                " actuator channels");
  }
  if (static_cast<int>(parts_.force_paths.size()) != channels_) {
    throw std::invalid_argument("ExperimentalExchange: one compensator and one restoring-force path per channel");
  }
  for (auto* c : parts_.compensators) {
    if (!c) throw std::invalid_argument("ExperimentalExchange: null compensator (use the pass-through one)");
  }
  if (!parts_.limits.empty() && static_cast<int>(parts_.limits.size()) != channels_) {
    throw std::invalid_argument("ExperimentalExchange: limits for every actuator channel or for none");
  }
  targets_ = Eigen::VectorXd::Zero(channels_);
  specimen_forces_ = Eigen::VectorXd::Zero(channels_);
  tracking_.resize(static_cast<std::size_t>(channels_));
  command_.test_id = feedback_.test_id = parts_.test_id;
  command_.run_id = parts_.run_id != 0 ? parts_.run_id : transport::draw_run_id();
  command_.channels = static_cast<std::uint8_t>(channels_);
}

void ExperimentalExchange::start(const Eigen::VectorXd& targets, std::span<const double> specimen_force_n) {
  if (targets.size() != channels_ || static_cast<int>(specimen_force_n.size()) != channels_) {
    throw std::invalid_argument("ExperimentalExchange::start: one target and one force per channel");
  }
  targets_ = targets;
  for (int c = 0; c < channels_; ++c) {
    parts_.compensators[c]->reset(targets_[c]);
    tracking_[c].reset(targets_[c], targets_[c]);
    specimen_forces_[c] = specimen_force_n[c];
    last_sent_m_[c] = targets_[c];  // the actuator holds the start
  }
  limit_stop_ = LimitStop{};
  saturated_exchanges_ = 0;
  exchange_ = 0;
  late_total_ = 0;
  feedback_age_ = 0;
  feedback_.step = -1;
}

bool ExperimentalExchange::commands_within_limits() {
  if (parts_.limits.empty()) return true;
  for (int c = 0; c < channels_; ++c) {
    const CoordinatorLimits& l = parts_.limits[c];
    const double x = command_.displacement_m[c], change = x - last_sent_m_[c];
    // A non-finite command fails both comparisons below, so test it first.
    if (!std::isfinite(x) || std::abs(x) > l.max_stroke_m) {
      limit_stop_ = {LimitStop::Kind::kStroke, c, x, l.max_stroke_m};
      return false;
    }
    if (std::abs(change) > l.max_increment_m) {
      limit_stop_ = {LimitStop::Kind::kIncrement, c, change, l.max_increment_m};
      return false;
    }
  }
  return true;
}

StepOutcome ExperimentalExchange::run_away() {
  constexpr std::uint32_t kPositionLimits = transport::kLimitStroke | transport::kLimitForce;
  if (parts_.stop_on_node_limits && (feedback_.limit_flags & kPositionLimits) != 0) {
    limit_stop_ = {LimitStop::Kind::kNodeLimit, -1, static_cast<double>(feedback_.limit_flags), 0.0};
    return StepOutcome::kRunAway;
  }
  if (feedback_.status & transport::kNodeEndStop) {
    limit_stop_ = {LimitStop::Kind::kEndStop, -1, 0.0, 0.0};
    return StepOutcome::kRunAway;
  }
  saturated_exchanges_ = feedback_.status & transport::kNodeValveSaturated ? saturated_exchanges_ + 1 : 0;
  if (parts_.max_valve_saturation_exchanges > 0 && saturated_exchanges_ > parts_.max_valve_saturation_exchanges) {
    limit_stop_ = {LimitStop::Kind::kValveSaturation, -1, static_cast<double>(saturated_exchanges_),
                   static_cast<double>(parts_.max_valve_saturation_exchanges)};
    return StepOutcome::kRunAway;
  }
  if (!parts_.limits.empty()) {
    for (int c = 0; c < channels_; ++c) {
      const double error = targets_[c] - feedback_.displacement_m[c];
      if (std::abs(error) > parts_.limits[c].max_tracking_error_m) {
        limit_stop_ = {LimitStop::Kind::kTrackingError, c, error, parts_.limits[c].max_tracking_error_m};
        return StepOutcome::kRunAway;
      }
    }
  }
  return StepOutcome::kOk;
}

StepOutcome ExperimentalExchange::exchange(const Eigen::VectorXd& targets, double time_s) {
  targets_ = targets;
  command_.step = exchange_;
  command_.time_s = time_s;
  for (int c = 0; c < channels_; ++c) command_.displacement_m[c] = parts_.compensators[c]->command(targets_[c]);
  if (!commands_within_limits()) return StepOutcome::kLimit;
  if (parts_.link->send(command_) != transport::LinkStatus::kOk) return StepOutcome::kLinkFailure;
  for (int c = 0; c < channels_; ++c) last_sent_m_[c] = command_.displacement_m[c];
  const transport::LinkStatus received = parts_.link->receive(feedback_);
  if (received == transport::LinkStatus::kRefused) return StepOutcome::kRefused;
  // How many commands behind the newest measurement is: 0 on time. Without any feedback
  // yet, the age counts from before the first command.
  feedback_age_ = exchange_ - (feedback_.step >= 0 ? feedback_.step : -1);
  if (received == transport::LinkStatus::kOk && feedback_age_ == 0) {
    // on time
  } else if ((received == transport::LinkStatus::kTimeout || received == transport::LinkStatus::kPeerLost) &&
             feedback_.step >= 0 && feedback_age_ > 0 && feedback_age_ <= parts_.max_feedback_age_periods) {
    // Real time: carry on with the newest measurement; the record says how old it is. A
    // node that answers late but answers keeps the age small; a silent one does not. The
    // age, not DDS liveliness, decides here: the 1 s lease lapses long after the age limit
    // has stopped a test on a dead node, while a lapse with recent feedback is a host that
    // stalled both processes for over a second, and the node answers again on waking.
    ++late_total_;
  } else {
    return StepOutcome::kLinkFailure;
  }
  ++exchange_;
  if (feedback_.status & transport::kNodeFault) return StepOutcome::kNodeFault;
  if (transport::has_non_finite_measurement(feedback_, channels_)) return StepOutcome::kNonFinite;
  if (const StepOutcome outcome = run_away(); outcome != StepOutcome::kOk) return outcome;
  for (int c = 0; c < channels_; ++c) {
    if (!parts_.limits.empty() && std::abs(feedback_.force_n[c]) > parts_.limits[c].max_force_n) {
      limit_stop_ = {LimitStop::Kind::kForce, c, feedback_.force_n[c], parts_.limits[c].max_force_n};
      return StepOutcome::kLimit;
    }
    parts_.compensators[c]->observe(targets_[c], feedback_.displacement_m[c]);
    tracking_[c].update(targets_[c], feedback_.displacement_m[c]);
  }
  for (int c = 0; c < channels_; ++c) {
    const RestoringForcePath& path = parts_.force_paths[c];
    specimen_forces_[c] = path.source == RestoringForceSource::kMeasuredForce
                              ? feedback_.force_n[c]
                              : path.stiffness_n_per_m * feedback_.displacement_m[c];
  }
  return StepOutcome::kOk;
}

void ExperimentalExchange::fill_channels(StepRecord& r) const {
  r.channels = static_cast<std::uint8_t>(channels_);
  for (int c = 0; c < channels_; ++c) {
    r.target_m[c] = targets_[c];
    r.command_m[c] = command_.displacement_m[c];
    r.measured_m[c] = feedback_.displacement_m[c];
    r.measured_force_n[c] = feedback_.force_n[c];
    r.specimen_restoring_force_n[c] = specimen_forces_[c];
    r.tracking_indicator_m2[c] = tracking_[c].value_m2();
    r.round_trip_s[c] = static_cast<double>(feedback_.round_trip_ns[c]) * 1e-9;
  }
  r.node_status = feedback_.status;
  r.limit_flags = feedback_.limit_flags;
}

}  // namespace rpsd::coordinator
