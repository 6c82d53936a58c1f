// The servo node's logic without I/O: it validates incoming commands, applies the newest on
// the next control tick, enforces the node's own limits whatever the coordinator sends,
// holds (or ramps to a safe position) when commands stop, drives the servo::Actuator and fills the
// feedback. The node process wraps it with the transport reader/writer and the pacer; call
// accept() and tick() from the same (control-loop) thread.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rpsd/node/servo_node_config.h"
#include "rpsd/servo/actuator.h"
#include "rpsd/transport/messages.h"

namespace rpsd::node {

// What accept() did with a command: kept it, or why it dropped it.
enum class CommandVerdict : std::uint8_t {
  kAccepted,
  kWrongTestId,
  kWrongSiteId,
  kWrongChannelCount,
  kNonFinite,     // a displacement of a used channel, or the time, is NaN or infinite
  kNotNewer,      // step not above the newest accepted one: a duplicate, reordered or negative
  kNotFollowing,  // the node has a latched fault or has ramped to its safe state
  // No command accepted yet and this one's step is beyond command_timeout_periods: the
  // test began without this node (a node restarted mid-test), which must not take it over
  // from its own initial position.
  kJoinedMidTest,
};
inline constexpr int kCommandVerdicts = 8;
const char* command_verdict_name(CommandVerdict verdict);

struct ServoNodeCounters {
  std::uint64_t accepted = 0;
  std::uint64_t superseded = 0;                              // accepted, then replaced by a newer command before a tick
  std::uint64_t applied = 0;                                 // commands taken by a tick
  std::array<std::uint64_t, kCommandVerdicts> by_verdict{};  // index: CommandVerdict
  std::uint64_t ticks = 0;
  std::uint64_t missed_periods = 0;                             // ticks without a new command, once commands began
  std::uint64_t holds = 0;                                      // times the watchdog began holding
  std::array<std::uint64_t, kLimitKinds> limit_activations{};   // per kind: a channel's limit began acting
  std::array<std::uint64_t, kLimitKinds> limit_active_ticks{};  // per kind: ticks it acted on any channel
  std::uint64_t faults = 0;                                     // fault latches (limit abort or actuator fault)
  std::uint64_t end_stop_ticks = 0;                             // ticks with a piston at the end of its stroke
  std::uint64_t valve_saturated_ticks = 0;                      // ticks with a servovalve fully open
  std::uint64_t actuator_no_replies = 0;
  std::uint64_t actuator_faults = 0;

  std::uint64_t dropped(CommandVerdict verdict) const { return by_verdict[static_cast<int>(verdict)]; }
  std::uint64_t dropped_total() const;
  std::uint64_t activations(LimitKind kind) const { return limit_activations[static_cast<int>(kind)]; }
};

// One limit activation: the tick on which a channel's limit began acting.
struct LimitEvent {
  std::uint64_t tick = 0;  // 0-based tick index since start()
  std::int64_t step = -1;  // the step of the command being followed
  int channel = 0;
  LimitKind kind = LimitKind::kStroke;
  LimitAction action = LimitAction::kClamp;
  double commanded_m = 0.0;  // the command the limit saw
  double applied_m = 0.0;    // the command sent to the actuator
  double observed = 0.0;     // what exceeded: |x| m, |dx|/T m/s, |F| N or |dx| m
  double bound = 0.0;        // the limit, in the same unit
};

class ServoNodeController {
 public:
  // Validates the config (std::invalid_argument naming the field) and checks that the
  // actuator has config.channels channels; sizes the event log. Not real-time safe.
  ServoNodeController(const ServoNodeConfig& config, servo::Actuator& actuator);

  // Starts the actuator at initial_displacement_m (one per channel, within the stroke),
  // clears counters, events and any latched fault or safe state. Throws. Not real-time safe.
  void start(std::span<const double> initial_displacement_m);

  // Checks an incoming command and keeps it as the pending one (a newer accepted command
  // replaces it); anything else is dropped, counted by reason and never applied. The first
  // command accepted after start() must have a step of at most command_timeout_periods
  // (a test's first is 0): a node that sees a test first later on, restarted while the
  // coordinator carried on, never follows it. Real-time safe.
  CommandVerdict accept(const transport::CommandSample& command);

  // One control period: applies the pending command (or holds/ramps after
  // command_timeout_periods periods without one), enforces the limits, exchanges with the
  // actuator and fills `out` (step/time of the command being followed, -1/0 before the
  // first, the measurement, status and limit flags). Before start(): kNodeFault, no
  // exchange. Real-time safe: no allocation, no locks, no exceptions.
  void tick(transport::FeedbackSample& out);

  const ServoNodeCounters& counters() const { return counters_; }
  // Limit activations in order, up to event_log_capacity; later ones are counted only.
  std::span<const LimitEvent> events() const { return events_; }
  std::uint64_t events_not_logged() const { return events_not_logged_; }

  // The step of the newest command accepted (-1 before the first).
  std::int64_t newest_accepted_step() const { return newest_accepted_step_; }
  bool faulted() const { return fault_; }
  bool holding() const { return holding_; }
  bool in_safe_state() const { return safe_state_; }
  // The command sent to the actuator on the last tick (the initial displacement before).
  std::span<const double> command_m() const { return {command_m_.data(), static_cast<std::size_t>(config_.channels)}; }
  const servo::ActuatorReading& reading() const { return reading_; }
  const ServoNodeConfig& config() const { return config_; }

 private:
  using Values = std::array<double, transport::kMaxChannels>;
  void choose_target();
  std::uint32_t apply_limits(Values& applied);
  void log(const LimitEvent& event);
  void latch_fault();

  ServoNodeConfig config_;
  servo::Actuator& actuator_;
  bool started_ = false;

  transport::CommandSample pending_;
  bool has_pending_ = false;
  std::int64_t newest_accepted_step_ = -1;
  std::int64_t followed_step_ = -1;
  double followed_time_s_ = 0.0;

  Values target_m_{};   // what the node is moving the command toward
  Values command_m_{};  // what it sent to the actuator last
  Values change_m_{};   // the last applied change of command (for the acceleration limit)
  servo::ActuatorReading reading_;

  bool commands_began_ = false;
  int missed_in_row_ = 0;
  bool holding_ = false;
  bool safe_state_ = false;
  bool fault_ = false;
  std::array<std::array<bool, kLimitKinds>, transport::kMaxChannels> limit_was_active_{};

  ServoNodeCounters counters_;
  std::vector<LimitEvent> events_;  // capacity reserved at construction, never grown past it
  std::uint64_t events_not_logged_ = 0;
};

}  // namespace rpsd::node
