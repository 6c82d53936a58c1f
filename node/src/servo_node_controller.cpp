#include "rpsd/node/servo_node_controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::node {

const char* command_verdict_name(CommandVerdict verdict) {
  switch (verdict) {
    case CommandVerdict::kAccepted:
      return "accepted";
    case CommandVerdict::kWrongTestId:
      return "wrong test id";
    case CommandVerdict::kWrongSiteId:
      return "wrong site id";
    case CommandVerdict::kWrongChannelCount:
      return "wrong channel count";
    case CommandVerdict::kNonFinite:
      return "non-finite value";
    case CommandVerdict::kNotNewer:
      return "step not newer";
    case CommandVerdict::kNotFollowing:
      return "node not following";
    case CommandVerdict::kJoinedMidTest:
      return "joined mid-test";
  }
  return "unknown";
}

std::uint64_t ServoNodeCounters::dropped_total() const {
  std::uint64_t total = 0;
  for (int v = 0; v < kCommandVerdicts; ++v) {
    if (v != static_cast<int>(CommandVerdict::kAccepted)) total += by_verdict[v];
  }
  return total;
}

ServoNodeController::ServoNodeController(const ServoNodeConfig& config, servo::Actuator& actuator)
    : config_(config), actuator_(actuator) {
  config_.validate();
  if (actuator.channels() != config_.channels) {
    throw std::invalid_argument("channels: the config has " + std::to_string(config_.channels) + ", the actuator " +
                                std::to_string(actuator.channels()));
  }
  events_.reserve(static_cast<std::size_t>(config_.event_log_capacity));
}

void ServoNodeController::start(std::span<const double> initial_displacement_m) {
  const int channels = config_.channels;
  if (static_cast<int>(initial_displacement_m.size()) != channels) {
    throw std::invalid_argument("ServoNodeController::start: " + std::to_string(channels) +
                                " initial displacements expected, got " +
                                std::to_string(initial_displacement_m.size()));
  }
  for (int c = 0; c < channels; ++c) {
    const double x0 = initial_displacement_m[c];
    if (!std::isfinite(x0) || std::abs(x0) > config_.limits[c].max_stroke_m) {
      throw std::invalid_argument("ServoNodeController::start: initial displacement of channel " + std::to_string(c) +
                                  " (" + std::to_string(x0) + " m) is not within limits[" + std::to_string(c) +
                                  "].max_stroke_m");
    }
  }
  started_ = false;
  actuator_.start(initial_displacement_m);
  reading_ = servo::ActuatorReading{};
  reading_.fresh = false;
  for (int c = 0; c < channels; ++c) {
    target_m_[c] = command_m_[c] = reading_.displacement_m[c] = initial_displacement_m[c];
  }
  has_pending_ = false;
  newest_accepted_step_ = followed_step_ = -1;
  followed_time_s_ = 0.0;
  commands_began_ = holding_ = safe_state_ = fault_ = false;
  missed_in_row_ = 0;
  limit_was_active_ = {};
  change_m_ = {};
  counters_ = ServoNodeCounters{};
  events_.clear();
  events_not_logged_ = 0;
  started_ = true;
}

CommandVerdict ServoNodeController::accept(const transport::CommandSample& command) {
  CommandVerdict verdict = CommandVerdict::kAccepted;
  const int channels = config_.channels;
  if (command.test_id != config_.test_id) {
    verdict = CommandVerdict::kWrongTestId;
  } else if (command.site_id != config_.site_id) {
    verdict = CommandVerdict::kWrongSiteId;
  } else if (command.channels != channels) {
    verdict = CommandVerdict::kWrongChannelCount;
  } else if (!std::isfinite(command.time_s) ||
             !std::all_of(command.displacement_m.begin(), command.displacement_m.begin() + channels,
                          [](double x) { return std::isfinite(x); })) {
    verdict = CommandVerdict::kNonFinite;
  } else if (command.step <= newest_accepted_step_) {
    verdict = CommandVerdict::kNotNewer;
  } else if (fault_ || safe_state_ || !started_) {
    verdict = CommandVerdict::kNotFollowing;
  } else if (newest_accepted_step_ < 0 && command.step > config_.command_timeout_periods) {
    verdict = CommandVerdict::kJoinedMidTest;
  }
  ++counters_.by_verdict[static_cast<int>(verdict)];
  if (verdict != CommandVerdict::kAccepted) return verdict;
  if (has_pending_) ++counters_.superseded;
  pending_ = command;
  has_pending_ = true;
  newest_accepted_step_ = command.step;
  ++counters_.accepted;
  return verdict;
}

void ServoNodeController::choose_target() {
  const int channels = config_.channels;
  if (fault_) {
    has_pending_ = false;
    target_m_ = command_m_;
    return;
  }
  if (has_pending_) {
    has_pending_ = false;
    std::copy_n(pending_.displacement_m.begin(), channels, target_m_.begin());
    followed_step_ = pending_.step;
    followed_time_s_ = pending_.time_s;
    ++counters_.applied;
    commands_began_ = true;
    missed_in_row_ = 0;
    holding_ = false;
    return;
  }
  // The watchdog runs once commands have begun: before the first, waiting is normal.
  if (commands_began_ && !safe_state_) {
    ++counters_.missed_periods;
    if (!holding_ && ++missed_in_row_ >= config_.command_timeout_periods) {
      holding_ = true;
      ++counters_.holds;
      target_m_ = command_m_;  // stop where the command is; a clamped command stops chasing
      safe_state_ = config_.on_command_loss == LossAction::kRampToSafe;
    }
  }
  if (safe_state_) {
    const double step_m = config_.safe_ramp_velocity_m_per_s * config_.control_period_s;
    for (int c = 0; c < channels; ++c) {
      const double to_go = config_.safe_position_m[c] - command_m_[c];
      target_m_[c] =
          std::abs(to_go) <= step_m ? config_.safe_position_m[c] : command_m_[c] + std::copysign(step_m, to_go);
    }
  }
}

void ServoNodeController::log(const LimitEvent& event) {
  if (events_.size() < events_.capacity()) {
    events_.push_back(event);  // within the reserved capacity: no allocation
  } else {
    ++events_not_logged_;
  }
}

void ServoNodeController::latch_fault() {
  if (!fault_) ++counters_.faults;
  fault_ = true;
  has_pending_ = false;
}

std::uint32_t ServoNodeController::apply_limits(Values& applied) {
  struct Violation {
    int channel;
    LimitKind kind;
    double observed, bound;
  };
  std::array<Violation, transport::kMaxChannels * kLimitKinds * 2> violations{};
  int count = 0;
  std::array<bool, kLimitKinds> kind_acted{};
  bool hold = false, ramp = false, abort = false;
  const int channels = config_.channels;
  const double period_s = config_.control_period_s;

  for (int c = 0; c < channels; ++c) {
    const ChannelLimits& limits = config_.limits[c];
    const double previous = command_m_[c], target = target_m_[c], change = target - previous;
    const double x_measured = reading_.displacement_m[c], force = reading_.force_n[c];
    const double velocity_step_m = limits.max_velocity_m_per_s * period_s;
    const double acceleration_step_m = limits.max_acceleration_m_per_s2 * period_s * period_s;
    const auto check = [&](bool exceeded, LimitKind kind, double observed, double bound) {
      if (!exceeded) return;
      violations[count++] = {c, kind, observed, bound};
      const LimitAction action = config_.actions.of(kind);
      hold = hold || action == LimitAction::kHold;
      ramp = ramp || action == LimitAction::kRampToSafe;
      abort = abort || action == LimitAction::kAbort;
    };
    // What is commanded, and what is measured (the interlocks).
    check(std::abs(target) > limits.max_stroke_m, LimitKind::kStroke, std::abs(target), limits.max_stroke_m);
    check(std::abs(change) > velocity_step_m, LimitKind::kVelocity, std::abs(change) / period_s,
          limits.max_velocity_m_per_s);
    check(std::abs(change) > limits.max_increment_m, LimitKind::kIncrement, std::abs(change), limits.max_increment_m);
    check(std::abs(change - change_m_[c]) > acceleration_step_m, LimitKind::kAcceleration,
          std::abs(change - change_m_[c]) / (period_s * period_s), limits.max_acceleration_m_per_s2);
    check(std::abs(x_measured) > limits.max_stroke_m, LimitKind::kStroke, std::abs(x_measured), limits.max_stroke_m);
    check(std::abs(force) > limits.max_force_n, LimitKind::kForce, std::abs(force), limits.max_force_n);

    // The clamped command: rate, increment and acceleration bounds, the stroke, and the force
    // guard, which keeps the command where F_measured + k (x - x_measured) stays within the
    // force limit: the force limit holds instead of tripping after the fact.
    const double rate_bound_m = std::min(velocity_step_m, limits.max_increment_m);
    double step = std::clamp(change, -rate_bound_m, rate_bound_m);
    step = std::clamp(step, change_m_[c] - acceleration_step_m, change_m_[c] + acceleration_step_m);
    double x = std::clamp(step == change ? target : previous + step, -limits.max_stroke_m, limits.max_stroke_m);
    if (limits.force_guard_stiffness_n_per_m > 0.0 && std::isfinite(limits.max_force_n)) {
      const double k = limits.force_guard_stiffness_n_per_m;
      const double highest = x_measured + (limits.max_force_n - force) / k;
      const double lowest = x_measured + (-limits.max_force_n - force) / k;
      if (x > highest || x < lowest) {
        const double bounded = std::clamp(x, std::min(lowest, highest), std::max(lowest, highest));
        check(true, LimitKind::kForce, std::abs(force + k * (x - x_measured)), limits.max_force_n);
        x = bounded;
      }
    }
    // A measured excursion: no further command in its direction.
    if (force > limits.max_force_n || x_measured > limits.max_stroke_m) x = std::min(x, x_measured);
    if (force < -limits.max_force_n || x_measured < -limits.max_stroke_m) x = std::max(x, x_measured);
    applied[c] = x;
  }

  // Hold, ramp and abort act on every channel (one channel frozen alone would load the setup
  // unevenly), from where the pistons are, not from where their commands were.
  if (abort) latch_fault();
  if (abort || hold || ramp) {
    for (int c = 0; c < channels; ++c) applied[c] = reading_.displacement_m[c];
  }
  if (ramp && !safe_state_) {
    safe_state_ = true;
    target_m_ = applied;
  }

  std::uint32_t flags = transport::kLimitNone;
  std::array<std::array<bool, kLimitKinds>, transport::kMaxChannels> active{};
  for (int i = 0; i < count; ++i) {
    const Violation& v = violations[i];
    const int k = static_cast<int>(v.kind);
    kind_acted[k] = true;
    flags |= limit_flag(v.kind);
    if (!limit_was_active_[v.channel][k] && !active[v.channel][k]) {
      ++counters_.limit_activations[k];
      log({counters_.ticks, followed_step_, v.channel, v.kind, config_.actions.of(v.kind), target_m_[v.channel],
           applied[v.channel], v.observed, v.bound});
    }
    active[v.channel][k] = true;
  }
  for (int k = 0; k < kLimitKinds; ++k) counters_.limit_active_ticks[k] += kind_acted[k] ? 1 : 0;
  limit_was_active_ = active;
  return flags;
}

void ServoNodeController::tick(transport::FeedbackSample& out) {
  const int channels = config_.channels;
  out.test_id = config_.test_id;
  out.site_id = config_.site_id;
  out.channels = static_cast<std::uint8_t>(channels);
  if (!started_) {
    out.step = -1;
    out.time_s = 0.0;
    out.status = transport::kNodeFault;
    out.limit_flags = transport::kLimitNone;
    return;
  }

  choose_target();
  Values applied = command_m_;
  const std::uint32_t flags = apply_limits(applied);

  const servo::ActuatorStatus status = actuator_.exchange(
      std::span<const double>(applied.data(), static_cast<std::size_t>(channels)), config_.control_period_s, reading_);
  for (int c = 0; c < channels; ++c) change_m_[c] = applied[c] - command_m_[c];
  command_m_ = applied;
  if (status == servo::ActuatorStatus::kNoReply) ++counters_.actuator_no_replies;
  if (status == servo::ActuatorStatus::kFault) {
    ++counters_.actuator_faults;
    latch_fault();
  }
  ++counters_.ticks;

  out.step = followed_step_;
  out.time_s = followed_time_s_;
  for (int c = 0; c < transport::kMaxChannels; ++c) {
    const bool used = c < channels;
    out.displacement_m[c] = used ? reading_.displacement_m[c] : 0.0;
    out.force_n[c] = used ? reading_.force_n[c] : 0.0;
  }
  out.status = transport::kNodeOk;
  if (flags != transport::kLimitNone) out.status |= transport::kNodeLimitActive;
  if (holding_) out.status |= transport::kNodeHolding;
  if (fault_) out.status |= transport::kNodeFault;
  if (reading_.at_end_stop) {
    out.status |= transport::kNodeEndStop;
    ++counters_.end_stop_ticks;
  }
  if (reading_.valve_saturated) {
    out.status |= transport::kNodeValveSaturated;
    ++counters_.valve_saturated_ticks;
  }
  out.limit_flags = flags;
}

}  // namespace rpsd::node
