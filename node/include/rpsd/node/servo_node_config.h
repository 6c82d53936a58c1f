// The servo node's typed configuration: identity, control period, the limits it enforces
// whatever the coordinator sends, and what it does when commands stop arriving.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include "rpsd/servo/actuator.h"
#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/envelope.h"
#include "rpsd/transport/messages.h"

namespace rpsd::node {

static_assert(servo::kMaxChannels == transport::kMaxChannels, "a node's actuator has as many channels as its messages");

// What a limit does when a command or a measurement exceeds it.
enum class LimitAction : std::uint8_t {
  kClamp,       // saturate the command at the bound (per channel) and keep following
  kHold,        // hold every channel where its piston is while the limit is exceeded
  kRampToSafe,  // ramp every channel to its safe position at the safe ramp velocity, and stay
  kAbort,       // latch a fault: every channel held where its piston is, status kNodeFault,
                // until the node is restarted
};

// What the node does when commands stop arriving (the watchdog).
enum class LossAction : std::uint8_t {
  kHold,        // keep commanding the last applied position; resume on the next command
  kRampToSafe,  // move the command to safe_position_m at safe_ramp_velocity_m_per_s and stay
};

enum class LimitKind : std::uint8_t { kStroke, kVelocity, kForce, kIncrement, kAcceleration };
inline constexpr int kLimitKinds = 5;

const char* limit_kind_name(LimitKind kind);
const char* limit_action_name(LimitAction action);
// The FeedbackSample::limit_flags bit of a limit kind.
std::uint32_t limit_flag(LimitKind kind);

// One channel's bounds; infinity means no limit (a node's are the rig's envelope unless
// tightened: limit_to_envelope).
struct ChannelLimits {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double max_stroke_m = kNone;          // |command| and |measured displacement|
  double max_velocity_m_per_s = kNone;  // |command change| / control period
  double max_force_n = kNone;           // |measured force|, and the force a command may ask for
  double max_increment_m = kNone;       // |command change| from one applied command to the next
  // The increment limit stated per second, so that it means the same at any control rate (its
  // action stays the increment's): limit_to_envelope makes max_increment_m this times the
  // control period. A file gives it or max_increment_m, not both.
  double max_increment_m_per_s = kNone;
  double max_acceleration_m_per_s2 = kNone;  // |change of command change| / control period^2
  // The stiffness the force guard predicts with (an upper bound of the specimen's): a command
  // is kept where F_measured + k (x_command - x_measured) stays within max_force_n. 0: no guard.
  double force_guard_stiffness_n_per_m = 0.0;
  // How hard the command brakes when it stops (a hold, an abort) and when it approaches the
  // stroke or the force guard's bound: a moving specimen stopped abruptly loads the rig with
  // its inertia. Infinity: it stops at once.
  double stop_deceleration_m_per_s2 = kNone;
  // A channel in force control (ServoNodeConfig::control): |force command|, clamped (infinity:
  // max_force_n's), and |force command change| / control period, clamped (required there). Its
  // stroke and velocity limits act on its measured displacement and end in the safe state.
  double max_force_command_n = kNone;
  double max_force_rate_n_per_s = kNone;
};

struct LimitActions {
  LimitAction stroke = LimitAction::kClamp;
  LimitAction velocity = LimitAction::kClamp;
  LimitAction force = LimitAction::kAbort;
  LimitAction increment = LimitAction::kClamp;
  LimitAction acceleration = LimitAction::kClamp;
  LimitAction of(LimitKind kind) const;
};

// The longest a node's watchdog may wait for a command (command_timeout_periods times the
// control period) before it holds.
inline constexpr double kMaxWatchdogTimeoutS = 10.0;

struct ServoNodeConfig {
  std::uint32_t test_id = 0;
  std::uint32_t site_id = 0;
  int channels = 1;
  double control_period_s = 1.0 / 1024.0;
  std::array<ChannelLimits, transport::kMaxChannels> limits{};  // per channel
  // Per channel: displacement control (the default) or force control (mixed control, issue
  // 30). A command must state each channel's mode as declared here, or the node faults.
  std::array<servo::ControlMode, transport::kMaxChannels> control{};
  LimitActions actions;
  // Consecutive control periods without a new command after which the node holds; at most
  // kMaxWatchdogTimeoutS in all.
  int command_timeout_periods = 10;
  LossAction on_command_loss = LossAction::kHold;
  std::array<double, transport::kMaxChannels> safe_position_m{};  // per channel, within the stroke
  double safe_ramp_velocity_m_per_s = 0.005;                      // at most each channel's max_velocity_m_per_s
  int event_log_capacity = 256;                                   // limit activations kept for after the run
  // What no measurement of a channel may reach, whatever the limits and their actions: a reading
  // at or beyond the rig's stroke or force capacity, or on an A/D converter's rail (where it may
  // stand for any value beyond), faults the node. Infinite: not known (limit_to_envelope and
  // read_through_converters set them).
  std::array<servo::Envelope, transport::kMaxChannels> rig{};
  std::array<servo::ReadingRanges, transport::kMaxChannels> rails{};

  // Throws std::invalid_argument naming the field ("limits[1].max_stroke_m: ..."). Not
  // real-time safe.
  void validate() const;
};

// Makes the rig's envelope every channel's limit: a limit left out (infinite) becomes the
// envelope's, and a limit beyond the envelope is refused (std::invalid_argument naming
// limits[c].key, a config::KeyError): a user may only tighten what the rig can do. A stated
// max_increment_m_per_s, held to the rig's velocity capacity, becomes max_increment_m at the
// node's control period. Not real-time safe.
void limit_to_envelope(ServoNodeConfig& config, const servo::Envelope& envelope);

// The channels' readings come through these converters: a reading on a rail faults the node.
// Not real-time safe.
void read_through_converters(ServoNodeConfig& config, const servo::ReadingRanges& ranges);
// The same, for a node whose limits are the only ones (a node file): each channel's stroke and
// force limit must lie strictly inside its converter's range, or std::invalid_argument naming
// limits[c].key and converters_key's converter ("actuator.servo.converters.force"). Call it after
// limit_to_envelope. Not real-time safe.
void limit_to_converters(ServoNodeConfig& config, const servo::ReadingRanges& ranges,
                         const std::string& converters_key);

}  // namespace rpsd::node
