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

#include "rpsd/node/channel_bounds.h"
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
  kNoRunId,        // run id 0: every command names its run
  kOtherRun,       // the node serves another run
  kUnknownWriter,  // the run the node serves, but not from the writer it follows (a forgery)
  kRunEnded,       // a command of the run the node has just ended
  kRateMismatch,   // the command states a control period other than the node's
  // A step further beyond the newest accepted one than a coordinator at this rate can have
  // gone: one step a period since, plus max_step_lead (a forgery, or a coordinator's bug).
  kImpossibleStep,
  kEndOfRun,  // not a drop: a run's end (the node frees itself if it is the run it serves)
  // A channel's control mode is not the one the node file declares (or a force channel's force
  // is not finite): the node, not the coordinator, says what drives the rig. Faults the node.
  kModeMismatch,
};
inline constexpr int kCommandVerdicts = 16;
const char* command_verdict_name(CommandVerdict verdict);

// What happened to the node's run: it took a run, the run ended, the node freed itself after a
// silence, or it refused a command of another run or writer, or with an impossible step.
struct RunEvent {
  enum class Kind : std::uint8_t { kBound, kEnded, kReleasedAfterSilence, kRefused };
  Kind kind = Kind::kBound;
  std::uint64_t tick = 0;
  std::uint64_t run_id = 0;                            // the run taken, ended or released; or the refused command's
  std::uint64_t writer = 0;                            // its writer
  std::uint64_t serving_run_id = 0;                    // kRefused: the run the node served then (0: none)
  std::int64_t step = -1;                              // the command's step
  CommandVerdict verdict = CommandVerdict::kAccepted;  // kRefused: why
};
const char* run_event_name(RunEvent::Kind kind);

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
  std::uint64_t runs = 0;  // runs taken (a node serves one at a time)

  std::uint64_t dropped(CommandVerdict verdict) const { return by_verdict[static_cast<int>(verdict)]; }
  std::uint64_t dropped_total() const;
  std::uint64_t activations(LimitKind kind) const { return limit_activations[static_cast<int>(kind)]; }
};

// What a limit event's bound is: one of the node's limits, or what no measurement may reach
// whatever the limits say (ServoNodeConfig::rig and rails), which faults the node.
enum class LimitCause : std::uint8_t {
  kLimit,          // limits[c]: the command or the measurement beyond it
  kConverterRail,  // a reading on its A/D converter's rail: the true value may be any beyond it
  kRigEnvelope,    // a measurement at or beyond the rig's stroke or force capacity
};
const char* limit_cause_name(LimitCause cause);

// One limit activation: the tick on which a channel's limit began acting.
struct LimitEvent {
  std::uint64_t tick = 0;  // 0-based tick index since start()
  std::int64_t step = -1;  // the step of the command being followed
  int channel = 0;
  LimitKind kind = LimitKind::kStroke;
  LimitAction action = LimitAction::kClamp;
  double commanded_m = 0.0;               // the command the limit saw
  double applied_m = 0.0;                 // the command sent to the actuator
  double observed = 0.0;                  // what exceeded: |x| m, |dx|/T m/s, |F| N or |dx| m
  double bound = 0.0;                     // the limit, in the same unit
  LimitCause cause = LimitCause::kLimit;  // not kLimit: the node faulted on a measurement (action kAbort)
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
  // replaces it); anything else is dropped, counted by reason and never applied. The node
  // serves one run at a time: the first command it accepts binds it to that command's run and
  // writer, and it refuses every other run and writer until the run ends (its end-of-run
  // command, or release_run()). A run's first command must have a step of at most
  // command_timeout_periods (a test's first is 0): a node that sees a test first later on,
  // restarted while the coordinator carried on, never follows it. Real-time safe.
  CommandVerdict accept(const transport::CommandSample& command) { return (this->*steps_.accept)(command); }

  // Frees the node from its run (the loop calls it after a silence: the coordinator is gone):
  // the node holds (or ramps to safe) as its watchdog would and may take another run. Nothing
  // when it serves none. Real-time safe.
  void release_run();
  // The run the node serves (0: none).
  std::uint64_t serving_run() const { return run_id_; }
  // Bindings, ends and refusals in order, up to event_log_capacity; later ones are counted only.
  std::span<const RunEvent> run_events() const { return run_events_; }
  std::uint64_t run_events_not_logged() const { return run_events_not_logged_; }

  // One control period: applies the pending command (or holds/ramps after
  // command_timeout_periods periods without one), enforces the limits, exchanges with the
  // actuator and fills `out` (step/time of the command being followed, -1/0 before the
  // first, the measurement, status and limit flags). Before start(): kNodeFault, no
  // exchange. Real-time safe: no allocation, no locks, no exceptions.
  void tick(transport::FeedbackSample& out) { (this->*steps_.tick)(out); }
  // Lock-step: accept(command) and, when accepted, tick(feedback) at once; false (feedback
  // untouched) when refused. Real-time safe.
  bool answer(const transport::CommandSample& command, transport::FeedbackSample& feedback) {
    return (this->*steps_.answer)(command, feedback);
  }

  const ServoNodeCounters& counters() const { return counters_; }
  // Limit activations in order, up to event_log_capacity; later ones are counted only.
  std::span<const LimitEvent> events() const { return events_; }
  std::uint64_t events_not_logged() const { return events_not_logged_; }

  // The step of the newest command accepted (-1 before the first), in the run served or, between
  // runs, the last run.
  std::int64_t newest_accepted_step() const { return last_accepted_step_; }
  bool faulted() const { return fault_; }
  // What latched the fault: the actuator's words (a lab controller's refusal, a silent
  // target) or the limit that aborted; empty when not faulted. NUL-terminated.
  const std::array<char, transport::kFaultTextBytes>& fault_text() const { return fault_text_; }
  bool holding() const { return holding_; }
  bool in_safe_state() const { return safe_state_; }
  // The command sent to the actuator on the last tick (the initial displacement before); a
  // channel in force control: its measured displacement.
  std::span<const double> command_m() const { return {command_m_.data(), static_cast<std::size_t>(config_.channels)}; }
  // Each channel's mode on the last tick: a channel declared in force control is in displacement
  // control until its first command, and again (at its measured position) after a fault or in
  // the safe state.
  std::span<const servo::ControlMode> control_mode() const {
    return {mode_.data(), static_cast<std::size_t>(config_.channels)};
  }
  // The force command sent on the last tick to each channel in force control (N).
  std::span<const double> force_command_n() const {
    return {force_command_n_.data(), static_cast<std::size_t>(config_.channels)};
  }
  const servo::ActuatorReading& reading() const { return reading_; }
  // The actuator's newest measurement (a tick's exchange that answered, or the reading at rest
  // noted after start()), and whether there is one: a node whose actuator can only be read by
  // an exchange has read nothing before its first tick. Its heartbeat carries both. A tick's
  // keeps the node's channels and the flags; the entries beyond the channels are not read.
  const servo::ActuatorReading& latest_measurement() const { return latest_measurement_; }
  bool has_measurement() const { return has_measurement_; }
  // After start(): the actuator's reading at rest, when it can be read without an exchange (a
  // simulated plant's sensors), so that a lock-step node tells its position before the first
  // command. Changes nothing the controller does. Not real-time safe.
  void note_reading_at_rest(const servo::ActuatorReading& reading);
  const ServoNodeConfig& config() const { return config_; }

 private:
  using Values = std::array<double, transport::kMaxChannels>;
  // The per-command and per-tick steps over N channels, N known to the compiler (0: any count,
  // config_.channels), chosen once at construction: one code, loops of a known length for a
  // node of one channel.
  template <int N>
  int count() const {
    return N > 0 ? N : config_.channels;
  }
  // The first N entries (N 0: the whole array, a few vector moves); a tick reads no other.
  template <int N>
  static void copy_channels(Values& to, const Values& from) {
    if constexpr (N > 0) {
      for (int c = 0; c < N; ++c) to[c] = from[c];
    } else {
      to = from;
    }
  }
  struct Steps {
    CommandVerdict (ServoNodeController::*accept)(const transport::CommandSample&);
    void (ServoNodeController::*tick)(transport::FeedbackSample&);
    bool (ServoNodeController::*answer)(const transport::CommandSample&, transport::FeedbackSample&);
  };
  template <int N>
  static constexpr Steps steps_of();
  template <int N>
  [[gnu::always_inline]] CommandVerdict accept_n(const transport::CommandSample& command);
  template <int N>
  [[gnu::always_inline]] void tick_n(transport::FeedbackSample& out);
  template <int N>
  bool answer_n(const transport::CommandSample& command, transport::FeedbackSample& feedback);
  template <int N>
  [[gnu::always_inline]] CommandVerdict check(const transport::CommandSample& command) const;
  void end_run(RunEvent::Kind why);
  void log_run(const RunEvent& event);
  template <int N>
  [[gnu::always_inline]] void choose_target();
  template <int N>
  [[gnu::always_inline]] std::uint32_t apply_limits(Values& applied);
  [[gnu::cold]] std::uint32_t log_limits(const std::array<std::uint8_t, transport::kMaxChannels>& exceeded,
                                         const Values& guard_observed, const Values& applied);
  template <int N>
  [[gnu::always_inline]] std::uint32_t check_measurement();
  template <int N>
  [[gnu::always_inline]] void keep_latest_measurement();
  // Channel c's reading, one on a rail or at the rig's capacity (or not a number): cold, so that
  // the tick's common case does not pay for what it logs.
  [[gnu::cold]] std::uint32_t check_reading(int c);
  std::uint32_t apply_force_limits();
  void leave_force_control();
  void log(const LimitEvent& event);
  void latch_fault();
  void keep_fault_text(std::string_view text) noexcept;
  void describe_fault(const LimitEvent& e) noexcept;

  ServoNodeConfig config_;
  servo::Actuator& actuator_;
  Steps steps_{};  // steps_of<1> or steps_of<0>, by config_.channels
  bool started_ = false;

  std::uint64_t run_id_ = 0, run_writer_ = 0;  // the run served and its writer (0: none)
  std::uint64_t ended_run_ = 0;                // the run ended last
  std::uint64_t ticks_since_accepted_ = 0;
  std::int64_t max_step_lead_ = 0;  // periods a step may lead the ticks since the last accepted one
  std::array<ChannelBounds, transport::kMaxChannels> bounds_{};  // per channel: its limits as a tick uses them
  static_assert(sizeof(transport::CommandSample::control_mode) == sizeof(std::uint64_t), "one word of modes");
  std::uint64_t declared_modes_ = 0, used_modes_mask_ = 0;  // check(): the channels' modes as one word
  std::array<std::uint8_t, 4> action_checks_{};  // per LimitAction: the checks of apply_limits whose kind does it
  RunEvent last_refusal_;                        // the last refusal logged: repeats of it are counted only
  std::vector<RunEvent> run_events_;             // capacity reserved at construction, never grown past it
  std::uint64_t run_events_not_logged_ = 0;

  // What a tick takes from the newest accepted command: only its step, time and used channels
  // are kept, not the whole sample.
  struct PendingCommand {
    std::int64_t step = 0;
    double time_s = 0.0;
    Values displacement_m{};
    Values force_n{};
  };
  PendingCommand pending_;
  bool has_pending_ = false;
  std::int64_t newest_accepted_step_ = -1;  // of the run served (-1: none yet, or no run)
  std::int64_t last_accepted_step_ = -1;    // what newest_accepted_step() reports
  std::int64_t followed_step_ = -1;
  double followed_time_s_ = 0.0;

  Values target_m_{};               // what the node is moving the command toward
  Values command_m_{};              // what it sent to the actuator last
  Values change_m_{};               // the last applied change of command (for the acceleration limit)
  bool any_force_channel_ = false;  // config_.control has one
  std::array<servo::ControlMode, transport::kMaxChannels> mode_{};  // each channel's, now
  Values force_target_n_{};                                         // a force channel's newest force command
  Values force_command_n_{};                                        // what it sent to the actuator last
  Values previous_measured_m_{};                                    // for the measured velocity of a force channel
  servo::ActuatorReading reading_;
  servo::ActuatorReading latest_measurement_;  // what latest_measurement() reports
  bool has_measurement_ = false;

  bool commands_began_ = false;
  int missed_in_row_ = 0;
  bool holding_ = false;
  bool safe_state_ = false;
  bool fault_ = false;
  std::array<char, transport::kFaultTextBytes> fault_text_{};
  std::array<std::array<bool, kLimitKinds>, transport::kMaxChannels> limit_was_active_{};
  // Per channel, stroke and force: the measurement was beyond what none may reach last tick.
  std::array<std::array<bool, 2>, transport::kMaxChannels> measurement_was_beyond_{};

  ServoNodeCounters counters_;
  std::vector<LimitEvent> events_;  // capacity reserved at construction, never grown past it
  std::uint64_t events_not_logged_ = 0;
};

}  // namespace rpsd::node
