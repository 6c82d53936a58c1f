#include "rpsd/node/servo_node_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "rpsd/config/key_error.h"

namespace rpsd::node {

const char* limit_kind_name(LimitKind kind) {
  switch (kind) {
    case LimitKind::kStroke:
      return "stroke";
    case LimitKind::kVelocity:
      return "velocity";
    case LimitKind::kForce:
      return "force";
    case LimitKind::kIncrement:
      return "increment";
    case LimitKind::kAcceleration:
      return "acceleration";
  }
  return "unknown";
}

const char* limit_action_name(LimitAction action) {
  switch (action) {
    case LimitAction::kClamp:
      return "clamp";
    case LimitAction::kHold:
      return "hold";
    case LimitAction::kRampToSafe:
      return "ramp_to_safe";
    case LimitAction::kAbort:
      return "abort";
  }
  return "unknown";
}

std::uint32_t limit_flag(LimitKind kind) {
  switch (kind) {
    case LimitKind::kStroke:
      return transport::kLimitStroke;
    case LimitKind::kVelocity:
      return transport::kLimitVelocity;
    case LimitKind::kForce:
      return transport::kLimitForce;
    case LimitKind::kIncrement:
      return transport::kLimitIncrement;
    case LimitKind::kAcceleration:
      return transport::kLimitAcceleration;
  }
  return transport::kLimitNone;
}

LimitAction LimitActions::of(LimitKind kind) const {
  switch (kind) {
    case LimitKind::kStroke:
      return stroke;
    case LimitKind::kVelocity:
      return velocity;
    case LimitKind::kForce:
      return force;
    case LimitKind::kIncrement:
      return increment;
    case LimitKind::kAcceleration:
      return acceleration;
  }
  return LimitAction::kAbort;
}

namespace {
// "name[c]" (appending, not operator+: GCC 12 reports a false -Wrestrict on "[" + s + "]").
std::string indexed(const char* name, int c) {
  std::string text(name);
  text += '[';
  text += std::to_string(c);
  text += ']';
  return text;
}

[[noreturn]] void fail(const std::string& field, const std::string& problem, double value) {
  std::ostringstream message;
  message << field << ": " << problem << ", got " << value;
  throw std::invalid_argument(message.str());
}
}  // namespace

void ServoNodeConfig::validate() const {
  if (channels < 1 || channels > transport::kMaxChannels) {
    fail("channels", "must be between 1 and " + std::to_string(transport::kMaxChannels), channels);
  }
  if (!(control_period_s > 0.0) || !std::isfinite(control_period_s))
    fail("control_period_s", "must be positive", control_period_s);
  for (int c = 0; c < channels; ++c) {
    const ChannelLimits& l = limits[c];
    const std::string at = indexed("limits", c) + ".";
    // Infinity is allowed (no limit); zero, negative and NaN are not.
    if (!(l.max_stroke_m > 0.0)) fail(at + "max_stroke_m", "must be positive (infinity: no limit)", l.max_stroke_m);
    if (!(l.max_velocity_m_per_s > 0.0))
      fail(at + "max_velocity_m_per_s", "must be positive (infinity: no limit)", l.max_velocity_m_per_s);
    if (!(l.max_force_n > 0.0)) fail(at + "max_force_n", "must be positive (infinity: no limit)", l.max_force_n);
    if (!(l.max_increment_m > 0.0))
      fail(at + "max_increment_m", "must be positive (infinity: no limit)", l.max_increment_m);
    if (!(l.max_increment_m_per_s > 0.0))
      fail(at + "max_increment_m_per_s", "must be positive (infinity: no limit)", l.max_increment_m_per_s);
    if (!(l.max_acceleration_m_per_s2 > 0.0)) {
      fail(at + "max_acceleration_m_per_s2", "must be positive (infinity: no limit)", l.max_acceleration_m_per_s2);
    }
    if (!(l.stop_deceleration_m_per_s2 > 0.0)) {
      fail(at + "stop_deceleration_m_per_s2", "must be positive (infinity: stop at once)",
           l.stop_deceleration_m_per_s2);
    }
    if (!(l.force_guard_stiffness_n_per_m >= 0.0) || !std::isfinite(l.force_guard_stiffness_n_per_m)) {
      fail(at + "force_guard_stiffness_n_per_m", "must be zero (no guard) or positive",
           l.force_guard_stiffness_n_per_m);
    }
    if (!(l.max_force_command_n > 0.0))
      fail(at + "max_force_command_n", "must be positive (infinity: max_force_n)", l.max_force_command_n);
    if (!(l.max_force_rate_n_per_s > 0.0))
      fail(at + "max_force_rate_n_per_s", "must be positive (infinity: no limit)", l.max_force_rate_n_per_s);
    if (control[c] == servo::ControlMode::kForce) {
      // A force loop may drive the piston anywhere the specimen lets it: it needs bounds of its own.
      if (!std::isfinite(std::min(l.max_force_command_n, l.max_force_n)))
        fail(at + "max_force_command_n", "a channel in force control needs a finite force command limit",
             l.max_force_command_n);
      if (!std::isfinite(l.max_force_rate_n_per_s))
        fail(at + "max_force_rate_n_per_s", "a channel in force control needs a force rate limit",
             l.max_force_rate_n_per_s);
      if (!std::isfinite(l.max_stroke_m) || !std::isfinite(l.max_velocity_m_per_s))
        fail(at + "max_stroke_m", "a channel in force control needs finite stroke and velocity limits", l.max_stroke_m);
    }
  }
  if (command_timeout_periods < 1) fail("command_timeout_periods", "must be at least 1", command_timeout_periods);
  // A watchdog that waits longer than this is none: the rig would follow nobody for minutes.
  if (const double timeout_s = command_timeout_periods * control_period_s; timeout_s > kMaxWatchdogTimeoutS) {
    std::ostringstream problem;
    problem << "times the control period (1/control_rate_hz) is the watchdog's timeout, at most "
            << kMaxWatchdogTimeoutS << " s, here " << timeout_s << " s";
    fail("command_timeout_periods", problem.str(), command_timeout_periods);
  }
  const bool ramps = on_command_loss == LossAction::kRampToSafe || actions.stroke == LimitAction::kRampToSafe ||
                     actions.velocity == LimitAction::kRampToSafe || actions.force == LimitAction::kRampToSafe ||
                     actions.increment == LimitAction::kRampToSafe || actions.acceleration == LimitAction::kRampToSafe;
  if (ramps) {
    if (!(safe_ramp_velocity_m_per_s > 0.0) || !std::isfinite(safe_ramp_velocity_m_per_s)) {
      fail("safe_ramp_velocity_m_per_s", "must be positive and finite", safe_ramp_velocity_m_per_s);
    }
    for (int c = 0; c < channels; ++c) {
      const std::string limits_at = indexed("limits", c);
      if (!std::isfinite(safe_position_m[c]) || std::abs(safe_position_m[c]) > limits[c].max_stroke_m) {
        fail(indexed("safe_position_m", c), "must lie within " + limits_at + ".max_stroke_m", safe_position_m[c]);
      }
      if (safe_ramp_velocity_m_per_s > limits[c].max_velocity_m_per_s) {
        fail("safe_ramp_velocity_m_per_s", "must not exceed " + limits_at + ".max_velocity_m_per_s",
             safe_ramp_velocity_m_per_s);
      }
      if (safe_ramp_velocity_m_per_s * control_period_s > limits[c].max_increment_m) {
        fail("safe_ramp_velocity_m_per_s", "times control_period_s must not exceed " + limits_at + ".max_increment_m",
             safe_ramp_velocity_m_per_s);
      }
    }
  }
  if (event_log_capacity < 0) fail("event_log_capacity", "must be zero or positive", event_log_capacity);
}

void limit_to_envelope(ServoNodeConfig& config, const servo::Envelope& envelope) {
  using servo::tighten_to_rig;
  for (int c = 0; c < config.channels; ++c) {
    ChannelLimits& l = config.limits[c];
    try {
      tighten_to_rig(l.max_stroke_m, envelope.stroke_m, "max_stroke_m", "stroke");
      tighten_to_rig(l.max_force_n, envelope.force_n, "max_force_n", "force capacity");
      tighten_to_rig(l.max_velocity_m_per_s, envelope.velocity_m_per_s, "max_velocity_m_per_s", "velocity capacity");
      // A force command never asks for more than the channel's force limit.
      if (l.max_force_command_n != ChannelLimits::kNone)
        tighten_to_rig(l.max_force_command_n, l.max_force_n, "max_force_command_n", "max_force_n");
      // Per second: the same increment at any rate the node runs at (left out, no increment limit).
      if (l.max_increment_m_per_s != ChannelLimits::kNone) {
        tighten_to_rig(l.max_increment_m_per_s, envelope.velocity_m_per_s, "max_increment_m_per_s",
                       "velocity capacity");
        l.max_increment_m = l.max_increment_m_per_s * config.control_period_s;
      }
    } catch (const config::KeyError& e) {
      throw e.under(indexed("limits", c));
    }
    config.rig[c] = envelope;
  }
}

void read_through_converters(ServoNodeConfig& config, const servo::ReadingRanges& ranges) {
  for (int c = 0; c < config.channels; ++c) config.rails[c] = ranges;
}

void limit_to_converters(ServoNodeConfig& config, const servo::ReadingRanges& ranges,
                         const std::string& converters_key) {
  read_through_converters(config, ranges);
  for (int c = 0; c < config.channels; ++c) {
    const ChannelLimits& l = config.limits[c];
    try {
      servo::require_readable(l.max_stroke_m, l.max_stroke_m == config.rig[c].stroke_m, ranges.displacement_m,
                              "max_stroke_m", converters_key + ".displacement", "m");
      servo::require_readable(l.max_force_n, l.max_force_n == config.rig[c].force_n, ranges.force_n, "max_force_n",
                              converters_key + ".force", "N");
    } catch (const config::KeyError& e) {
      throw e.under(indexed("limits", c));
    }
  }
}

}  // namespace rpsd::node
