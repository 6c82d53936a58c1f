#include "rpsd/node/servo_node_controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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
    case CommandVerdict::kNoRunId:
      return "no run id";
    case CommandVerdict::kOtherRun:
      return "another run";
    case CommandVerdict::kUnknownWriter:
      return "unknown writer";
    case CommandVerdict::kRunEnded:
      return "run ended";
    case CommandVerdict::kRateMismatch:
      return "control rate differs";
    case CommandVerdict::kImpossibleStep:
      return "impossible step";
    case CommandVerdict::kEndOfRun:
      return "end of run";
    case CommandVerdict::kModeMismatch:
      return "control mode differs";
  }
  return "unknown";
}

const char* run_event_name(RunEvent::Kind kind) {
  switch (kind) {
    case RunEvent::Kind::kBound:
      return "took run";
    case RunEvent::Kind::kEnded:
      return "run ended";
    case RunEvent::Kind::kReleasedAfterSilence:
      return "freed after silence";
    case RunEvent::Kind::kRefused:
      return "refused";
  }
  return "unknown";
}

const char* limit_cause_name(LimitCause cause) {
  switch (cause) {
    case LimitCause::kLimit:
      return "limit";
    case LimitCause::kConverterRail:
      return "converter_rail";
    case LimitCause::kRigEnvelope:
      return "rig_envelope";
  }
  return "unknown";
}

std::uint64_t ServoNodeCounters::dropped_total() const {
  std::uint64_t total = 0;
  for (int v = 0; v < kCommandVerdicts; ++v) {
    if (v != static_cast<int>(CommandVerdict::kAccepted) && v != static_cast<int>(CommandVerdict::kEndOfRun)) {
      total += by_verdict[v];
    }
  }
  return total;
}

namespace {

// What each bit of a channel's exceeded mask (apply_limits) stands for, in the order the checks
// run: the command's stroke, velocity, increment and acceleration, the measured stroke and force,
// and the force guard's prediction.
constexpr std::array<LimitKind, 7> kCheckKind = {LimitKind::kStroke,       LimitKind::kVelocity, LimitKind::kIncrement,
                                                 LimitKind::kAcceleration, LimitKind::kStroke,   LimitKind::kForce,
                                                 LimitKind::kForce};
constexpr int kForceCheck = 5, kGuardCheck = 6;
constexpr std::uint8_t bit(bool exceeded, int check) { return static_cast<std::uint8_t>(exceeded ? 1u << check : 0u); }

}  // namespace

ServoNodeController::ServoNodeController(const ServoNodeConfig& config, servo::Actuator& actuator)
    : config_(config), actuator_(actuator) {
  config_.validate();
  if (actuator.channels() != config_.channels) {
    throw std::invalid_argument("channels: the config has " + std::to_string(config_.channels) + ", the actuator " +
                                std::to_string(actuator.channels()));
  }
  for (int c = 0; c < config_.channels; ++c) {
    if (config_.control[c] != servo::ControlMode::kForce) continue;
    if (!actuator.controls_force(c)) {
      throw std::invalid_argument("control[" + std::to_string(c) + "]: channel " + std::to_string(c) +
                                  " is declared in force control, but its actuator cannot control force");
    }
    any_force_channel_ = true;
  }
  for (int c = 0; c < config_.channels; ++c) {
    bounds_[c] = ChannelBounds::of(config_.limits[c], config_.control_period_s);
    bounds_[c].read_within(config_.rig[c], config_.rails[c]);
  }
  // The control modes a command must state, as the bytes of CommandSample::control_mode.
  std::array<std::uint8_t, transport::kMaxChannels> declared{}, used{};
  for (int c = 0; c < config_.channels; ++c) {
    declared[c] =
        config_.control[c] == servo::ControlMode::kForce ? transport::kForceControl : transport::kDisplacementControl;
    used[c] = 0xff;
  }
  std::memcpy(&declared_modes_, declared.data(), sizeof declared_modes_);
  std::memcpy(&used_modes_mask_, used.data(), sizeof used_modes_mask_);
  for (int check = 0; check < kGuardCheck; ++check)
    action_checks_[static_cast<int>(config_.actions.of(kCheckKind[check]))] |= bit(true, check);
  // A node of one channel (every in-process site of one actuator) steps with loops of a length
  // the compiler knows; any other count with the same code over config_.channels.
  steps_ = config_.channels == 1 ? steps_of<1>() : steps_of<0>();
  events_.reserve(static_cast<std::size_t>(config_.event_log_capacity));
  run_events_.reserve(static_cast<std::size_t>(config_.event_log_capacity));
  // A coordinator sends one command a period: after commands were lost (a partition, a stall
  // of either host) its step leads the node's ticks by at most the stall, taken as up to a
  // second here (and never less than the watchdog's periods).
  const double second_in_periods = std::ceil(1.0 / config_.control_period_s);
  max_step_lead_ = std::max<std::int64_t>(config_.command_timeout_periods,
                                          static_cast<std::int64_t>(std::min(second_in_periods, 1e12)));
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
  latest_measurement_ = servo::ActuatorReading{};
  has_measurement_ = false;
  for (int c = 0; c < channels; ++c) {
    target_m_[c] = command_m_[c] = reading_.displacement_m[c] = initial_displacement_m[c];
  }
  has_pending_ = false;
  newest_accepted_step_ = last_accepted_step_ = followed_step_ = -1;
  followed_time_s_ = 0.0;
  run_id_ = run_writer_ = ended_run_ = 0;
  ticks_since_accepted_ = 0;
  last_refusal_ = RunEvent{};
  run_events_.clear();
  run_events_not_logged_ = 0;
  commands_began_ = holding_ = safe_state_ = fault_ = false;
  fault_text_ = {};
  missed_in_row_ = 0;
  limit_was_active_ = {};
  measurement_was_beyond_ = {};
  change_m_ = {};
  // Every channel starts in displacement control, holding its initial position; a force channel
  // enters force control with its first command, from the force it measures then.
  mode_.fill(servo::ControlMode::kDisplacement);
  force_target_n_ = force_command_n_ = {};
  previous_measured_m_ = target_m_;
  counters_ = ServoNodeCounters{};
  events_.clear();
  events_not_logged_ = 0;
  started_ = true;
}

void ServoNodeController::note_reading_at_rest(const servo::ActuatorReading& reading) {
  latest_measurement_ = reading;
  has_measurement_ = true;
}

namespace {
// One control rate, to a rounding error (1/f on one side, dt/iterations on the other).
bool same_period(double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(std::abs(a), std::abs(b)); }
}  // namespace

// Inline: once a command, from accept() alone (this file).
template <int N>
inline CommandVerdict ServoNodeController::check(const transport::CommandSample& command) const {
  const int channels = count<N>();
  if (command.test_id != config_.test_id) return CommandVerdict::kWrongTestId;
  if (command.site_id != config_.site_id) return CommandVerdict::kWrongSiteId;
  if (command.end_of_run) return CommandVerdict::kEndOfRun;
  // Whose command it is comes before what it says: another run's step means nothing here.
  if (command.run_id == 0) return CommandVerdict::kNoRunId;
  if (run_id_ != 0) {
    if (command.run_id != run_id_) return CommandVerdict::kOtherRun;
    if (command.writer != run_writer_) return CommandVerdict::kUnknownWriter;
  } else if (command.run_id == ended_run_) {
    return CommandVerdict::kRunEnded;
  }
  if (command.channels != channels) return CommandVerdict::kWrongChannelCount;
  if (!std::isfinite(command.time_s)) return CommandVerdict::kNonFinite;
  // A plain loop: std::all_of's unrolling by four costs more than it saves on a few channels.
  for (int c = 0; c < channels; ++c) {
    if (!std::isfinite(command.displacement_m[c])) return CommandVerdict::kNonFinite;
  }
  if (command.control_period_s != 0.0 && !same_period(command.control_period_s, config_.control_period_s)) {
    return CommandVerdict::kRateMismatch;
  }
  // Each channel's mode as its file declares it (the entries beyond the channels not compared),
  // and a finite force for each force channel.
  std::uint64_t modes = 0;
  std::memcpy(&modes, command.control_mode.data(), sizeof modes);
  if ((modes & used_modes_mask_) != declared_modes_) return CommandVerdict::kModeMismatch;
  for (int c = 0; c < channels && any_force_channel_; ++c) {
    if (config_.control[c] == servo::ControlMode::kForce && !std::isfinite(command.force_n[c]))
      return CommandVerdict::kModeMismatch;
  }
  if (command.step <= newest_accepted_step_) return CommandVerdict::kNotNewer;
  if (fault_ || safe_state_ || !started_) return CommandVerdict::kNotFollowing;
  if (newest_accepted_step_ < 0) {
    if (command.step > config_.command_timeout_periods) return CommandVerdict::kJoinedMidTest;
  } else {
    // step > newest here, so neither side overflows: allowed is at most ~2^62.
    const auto allowed = static_cast<std::int64_t>(
        std::min<std::uint64_t>(1 + ticks_since_accepted_ + static_cast<std::uint64_t>(max_step_lead_), 1ull << 62));
    if (command.step - allowed > newest_accepted_step_) return CommandVerdict::kImpossibleStep;
  }
  return CommandVerdict::kAccepted;
}

template <int N>
inline CommandVerdict ServoNodeController::accept_n(const transport::CommandSample& command) {
  const CommandVerdict verdict = check<N>(command);
  ++counters_.by_verdict[static_cast<int>(verdict)];
  switch (verdict) {
    case CommandVerdict::kAccepted:
      break;
    case CommandVerdict::kEndOfRun:
      // Only the run's own writer ends it; another's end, or a repeat, changes nothing.
      if (run_id_ != 0 && command.run_id == run_id_ && command.writer == run_writer_) {
        end_run(RunEvent::Kind::kEnded);
      }
      return verdict;
    case CommandVerdict::kModeMismatch:
      // The run's own command asks the rig for what its file does not allow: stop following.
      if (!fault_ && started_) {
        int c = 0;
        while (c + 1 < config_.channels && command.control_mode[c] == static_cast<std::uint8_t>(config_.control[c]))
          ++c;
        std::snprintf(fault_text_.data(), fault_text_.size(),
                      "command of step %lld puts channel %d in control mode %u, declared %s: refused",
                      static_cast<long long>(command.step), c, static_cast<unsigned>(command.control_mode[c]),
                      servo::control_mode_name(config_.control[c]));
      }
      latch_fault();
      return verdict;
    case CommandVerdict::kOtherRun:
    case CommandVerdict::kUnknownWriter:
    case CommandVerdict::kRunEnded:
    case CommandVerdict::kRateMismatch:
    case CommandVerdict::kImpossibleStep: {
      const RunEvent refusal{
          RunEvent::Kind::kRefused, counters_.ticks, command.run_id, command.writer, run_id_, command.step, verdict};
      // A stream of the same refusal is logged once (and counted by verdict).
      if (refusal.run_id != last_refusal_.run_id || refusal.writer != last_refusal_.writer ||
          refusal.verdict != last_refusal_.verdict || refusal.serving_run_id != last_refusal_.serving_run_id) {
        log_run(refusal);
        last_refusal_ = refusal;
      }
      return verdict;
    }
    default:
      return verdict;
  }
  if (run_id_ == 0) {
    run_id_ = command.run_id;
    run_writer_ = command.writer;
    ++counters_.runs;
    log_run({RunEvent::Kind::kBound, counters_.ticks, run_id_, run_writer_, 0, command.step, verdict});
  }
  if (has_pending_) ++counters_.superseded;
  pending_.step = command.step;
  pending_.time_s = command.time_s;
  // A tick reads only the node's channels.
  copy_channels<N>(pending_.displacement_m, command.displacement_m);
  if (any_force_channel_) copy_channels<N>(pending_.force_n, command.force_n);  // read by force channels only
  has_pending_ = true;
  newest_accepted_step_ = last_accepted_step_ = command.step;
  ticks_since_accepted_ = 0;
  ++counters_.accepted;
  return verdict;
}

void ServoNodeController::release_run() {
  if (run_id_ != 0) end_run(RunEvent::Kind::kReleasedAfterSilence);
}

void ServoNodeController::end_run(RunEvent::Kind why) {
  log_run({why, counters_.ticks, run_id_, run_writer_, 0, newest_accepted_step_, CommandVerdict::kAccepted});
  ended_run_ = run_id_;
  run_id_ = run_writer_ = 0;
  last_refusal_ = RunEvent{};
  // Stop as the watchdog would (hold, or ramp to safe), and wait for the next run without
  // calling the wait a loss.
  has_pending_ = false;
  if (commands_began_ && !holding_ && !fault_) {
    holding_ = true;
    ++counters_.holds;
    target_m_ = command_m_;
    force_target_n_ = force_command_n_;
    safe_state_ = safe_state_ || config_.on_command_loss == LossAction::kRampToSafe;
  }
  commands_began_ = false;
  missed_in_row_ = 0;
  newest_accepted_step_ = followed_step_ = -1;
  followed_time_s_ = 0.0;
}

void ServoNodeController::log_run(const RunEvent& event) {
  if (run_events_.size() < run_events_.capacity()) {
    run_events_.push_back(event);  // within the reserved capacity: no allocation
  } else {
    ++run_events_not_logged_;
  }
}

// Inline: once a tick, from tick() alone (this file).
template <int N>
inline void ServoNodeController::choose_target() {
  const int channels = count<N>();
  if (fault_) {
    has_pending_ = false;
    target_m_ = command_m_;
    return;
  }
  if (has_pending_) {
    has_pending_ = false;
    // Only the node's channels are read.
    copy_channels<N>(target_m_, pending_.displacement_m);
    if (any_force_channel_) copy_channels<N>(force_target_n_, pending_.force_n);
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
      target_m_ = command_m_;              // stop where the command is; a clamped command stops chasing
      force_target_n_ = force_command_n_;  // a force channel holds its force
      safe_state_ = config_.on_command_loss == LossAction::kRampToSafe;
    }
  }
  if (safe_state_) {
    // Every channel moves along one straight line and all arrive together, the farthest at the
    // safe velocity: the actuators of one specimen (an experimental setup) take it back along a
    // straight path of their strokes, which linear geometry maps to a straight path of its DOFs,
    // not one actuator after the other.
    const double step_m = config_.safe_ramp_velocity_m_per_s * config_.control_period_s;
    double farthest_m = 0.0;
    for (int c = 0; c < channels; ++c)
      farthest_m = std::max(farthest_m, std::abs(config_.safe_position_m[c] - command_m_[c]));
    for (int c = 0; c < channels; ++c) {
      const double to_go = config_.safe_position_m[c] - command_m_[c];
      target_m_[c] = farthest_m <= step_m ? config_.safe_position_m[c] : command_m_[c] + step_m * (to_go / farthest_m);
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

// Inline: once a tick, from tick() alone (this file).
template <int N>
inline std::uint32_t ServoNodeController::apply_limits(Values& applied) {
  const int channels = count<N>();
  const double period_s = config_.control_period_s;
  // What is asked for, and what is measured (the interlocks): one bit per check exceeded, every
  // check on every channel; what a limit does and says is worked out below only when one acts.
  std::array<std::uint8_t, transport::kMaxChannels> exceeded{};
  std::uint8_t any = 0;
  for (int c = 0; c < channels; ++c) {
    const ChannelBounds& b = bounds_[c];
    const double target = target_m_[c], change = target - command_m_[c];
    const double x_measured = reading_.displacement_m[c], force = reading_.force_n[c];
    std::uint8_t e = bit(std::abs(force) > b.force_n, kForceCheck);
    if (mode_[c] != servo::ControlMode::kForce) {  // a force channel's other checks: apply_force_limits
      const double acceleration = std::abs(change - change_m_[c]) / (period_s * period_s);
      e |= bit(std::abs(target) > b.stroke_m, 0) | bit(std::abs(change) > b.velocity_step_m, 1) |
           bit(std::abs(change) > b.increment_m, 2) | bit(acceleration > b.acceleration_m_per_s2, 3) |
           bit(std::abs(x_measured) > b.stroke_m, 4);
    }
    exceeded[c] = e;
    any |= e;
  }
  bool stopping_for_limit = false, ramp_begins = false;
  if (any != 0) {
    if (any & action_checks_[static_cast<int>(LimitAction::kAbort)]) latch_fault();
    ramp_begins = (any & action_checks_[static_cast<int>(LimitAction::kRampToSafe)]) != 0 && !safe_state_;
    if (ramp_begins) safe_state_ = true;  // choose_target ramps from the next tick on
    stopping_for_limit = (any & action_checks_[static_cast<int>(LimitAction::kHold)]) != 0;
  }
  // A hold or an abort brings the command to rest at the stop deceleration; the safe ramp
  // moves it at the safe velocity.
  const bool stopping = fault_ || (holding_ && !safe_state_) || stopping_for_limit || ramp_begins;

  // The command each channel gets: the velocity and increment bounds, the acceleration bound,
  // and position bounds (the stroke, the force guard, no further motion into a measured
  // excursion) approached no faster than the stop deceleration can brake.
  bool guarded = false;
  Values guard_observed;  // read only where the guard acted, which wrote it
  for (int c = 0; c < channels; ++c) {
    const ChannelBounds& b = bounds_[c];
    const double x_command = command_m_[c];
    const double x_measured = reading_.displacement_m[c], force = reading_.force_n[c];
    if (mode_[c] == servo::ControlMode::kForce) {
      applied[c] = x_measured;  // where it would hold, should it leave force control
      continue;
    }
    const double v_command = change_m_[c] / period_s;
    const double wanted = stopping ? x_command : target_m_[c];
    const double asked = (wanted - x_command) / period_s;
    double v = std::clamp(asked, -b.max_speed_m_per_s, b.max_speed_m_per_s);
    if (stopping ? b.stop_brakes : b.follow_accelerates) {
      const double a_step = stopping ? b.stop_step_m_per_s : b.follow_step_m_per_s;
      v = std::clamp(v, v_command - a_step, v_command + a_step);
    }

    double high = b.stroke_m, low = -b.stroke_m;
    if (b.force_guard) {
      const double k = b.guard_stiffness_n_per_m;
      const double guard_high = x_measured + (b.force_n - force) / k;
      const double guard_low = x_measured + (-b.force_n - force) / k;
      const double next = x_command + v * period_s;
      if (next > guard_high || next < guard_low) {
        exceeded[c] |= bit(true, kGuardCheck);
        guarded = true;
        guard_observed[c] = std::abs(force + k * (next - x_measured));  // the force it predicted
      }
      high = std::min(high, guard_high);
      low = std::max(low, guard_low);
    }
    if (force > b.force_n || x_measured > b.stroke_m) high = std::min(high, x_command);
    if (force < -b.force_n || x_measured < -b.stroke_m) low = std::max(low, x_command);
    // Past a bound the command only stops going further (it is not pulled back: a force
    // guard that chased the measured force would feed the oil column's resonance). Both
    // braking speeds are >= 0, so only the bound ahead can change v: the one it moves toward
    // (none when it stays), the same v as clamping between both.
    if (v > 0.0) v = std::min(v, b.braking_speed(high - x_command, period_s));
    if (v < 0.0) v = std::max(v, -b.braking_speed(x_command - low, period_s));
    // Unchanged by any bound: exactly the target, as sent.
    applied[c] = v == asked ? wanted : x_command + v * period_s;
  }

  if (any == 0 && !guarded) {  // no limit acted on any channel: nothing to log or count
    limit_was_active_ = {};
    return transport::kLimitNone;
  }
  return log_limits(exceeded, guard_observed, applied);
}

std::uint32_t ServoNodeController::log_limits(const std::array<std::uint8_t, transport::kMaxChannels>& exceeded,
                                              const Values& guard_observed, const Values& applied) {
  // The checks in the order they ran (each channel's checks of the command and the measurement,
  // then each channel's force guard), each with what it saw: the same values apply_limits compared.
  const int channels = config_.channels;
  const double period_s = config_.control_period_s;
  std::uint32_t flags = transport::kLimitNone;
  std::array<bool, kLimitKinds> kind_acted{};
  std::array<std::array<bool, kLimitKinds>, transport::kMaxChannels> active{};
  const auto acted = [&](int c, int check, double observed, double bound) {
    if ((exceeded[c] & (1u << check)) == 0) return;
    const LimitKind kind = kCheckKind[check];
    const int k = static_cast<int>(kind);
    kind_acted[k] = true;
    flags |= limit_flag(kind);
    if (!limit_was_active_[c][k] && !active[c][k]) {
      ++counters_.limit_activations[k];
      log({counters_.ticks, followed_step_, c, kind, config_.actions.of(kind), target_m_[c], applied[c], observed,
           bound});
    }
    active[c][k] = true;
  };
  for (int c = 0; c < channels; ++c) {
    const ChannelLimits& limits = config_.limits[c];
    const double change = target_m_[c] - command_m_[c];
    const double x_measured = reading_.displacement_m[c], force = reading_.force_n[c];
    if (mode_[c] == servo::ControlMode::kForce) {
      acted(c, kForceCheck, std::abs(force), limits.max_force_n);
      continue;
    }
    acted(c, 0, std::abs(target_m_[c]), limits.max_stroke_m);
    acted(c, 1, std::abs(change) / period_s, limits.max_velocity_m_per_s);
    acted(c, 2, std::abs(change), limits.max_increment_m);
    acted(c, 3, std::abs(change - change_m_[c]) / (period_s * period_s), limits.max_acceleration_m_per_s2);
    acted(c, 4, std::abs(x_measured), limits.max_stroke_m);
    acted(c, kForceCheck, std::abs(force), limits.max_force_n);
  }
  for (int c = 0; c < channels; ++c) {
    if ((exceeded[c] & (1u << kGuardCheck)) == 0) continue;
    acted(c, kGuardCheck, guard_observed[c], config_.limits[c].max_force_n);
  }
  for (int k = 0; k < kLimitKinds; ++k) counters_.limit_active_ticks[k] += kind_acted[k] ? 1 : 0;
  limit_was_active_ = active;
  return flags;
}

// Inline: once a tick, from tick() alone (this file); the rare reading goes to check_reading.
template <int N>
inline std::uint32_t ServoNodeController::check_measurement() {
  // Whatever the actuator (a simulated plant, a hardware adapter) and whatever the limits'
  // actions: a reading on a converter's rail may stand for any value beyond it, and one at the
  // rig's stroke or force capacity is an end stop or a rig overloaded. Either faults the node.
  std::uint32_t flags = transport::kLimitNone;
  const int channels = count<N>();
  for (int c = 0; c < channels; ++c) {
    if (bounds_[c].quiet(reading_.displacement_m[c], reading_.force_n[c])) {
      measurement_was_beyond_[c] = {false, false};
    } else {
      flags |= check_reading(c);
    }
  }
  return flags;
}

std::uint32_t ServoNodeController::check_reading(int c) {
  std::uint32_t flags = transport::kLimitNone;
  const struct {
    LimitKind kind;
    double reading, rig;
    const servo::ConverterRange& rail;
  } quantities[2] = {
      {LimitKind::kStroke, reading_.displacement_m[c], config_.rig[c].stroke_m, config_.rails[c].displacement_m},
      {LimitKind::kForce, reading_.force_n[c], config_.rig[c].force_n, config_.rails[c].force_n}};
  for (int q = 0; q < 2; ++q) {
    const auto& [kind, reading, rig, rail] = quantities[q];
    const bool on_rail = rail.at_rail(reading);
    const bool beyond_rig = std::abs(reading) >= rig;
    if (!on_rail && !beyond_rig) {
      measurement_was_beyond_[c][q] = false;
      continue;
    }
    flags |= limit_flag(kind);
    if (!measurement_was_beyond_[c][q]) {
      measurement_was_beyond_[c][q] = true;
      ++counters_.limit_activations[static_cast<int>(kind)];
      const double bound = on_rail ? (reading >= rail.high ? rail.high : -rail.low) : rig;
      log({counters_.ticks, followed_step_, c, kind, LimitAction::kAbort, target_m_[c], command_m_[c],
           std::abs(reading), bound, on_rail ? LimitCause::kConverterRail : LimitCause::kRigEnvelope});
    }
    latch_fault();
  }
  return flags;
}

std::uint32_t ServoNodeController::apply_force_limits() {
  // A force channel's piston goes wherever the specimen lets it (a softening or broken specimen
  // lets it run away): its measured stroke and velocity stop it whatever the limits' actions.
  // Its force command is held to max_force_command_n and max_force_rate_n_per_s.
  std::uint32_t flags = transport::kLimitNone;
  const double period_s = config_.control_period_s;
  for (int c = 0; c < config_.channels; ++c) {
    if (config_.control[c] != servo::ControlMode::kForce) continue;
    const ChannelLimits& l = config_.limits[c];
    const double x = reading_.displacement_m[c];
    const double velocity = std::abs(x - previous_measured_m_[c]) / period_s;
    previous_measured_m_[c] = x;
    if (mode_[c] != servo::ControlMode::kForce) continue;
    const struct {
      LimitKind kind;
      double observed, bound;
    } measured[2] = {{LimitKind::kStroke, std::abs(x), l.max_stroke_m},
                     {LimitKind::kVelocity, velocity, l.max_velocity_m_per_s}};
    for (const auto& [kind, observed, bound] : measured) {
      if (!(observed > bound)) continue;
      flags |= limit_flag(kind);
      const int k = static_cast<int>(kind);
      if (!limit_was_active_[c][k]) {
        limit_was_active_[c][k] = true;
        ++counters_.limit_activations[k];
        log({counters_.ticks, followed_step_, c, kind, LimitAction::kAbort, x, x, observed, bound});
      }
      latch_fault();
    }
    if (fault_) continue;
    const double cap = std::min(l.max_force_command_n, l.max_force_n);
    const double step_n = l.max_force_rate_n_per_s * period_s;
    const double wanted = std::clamp(force_target_n_[c], -cap, cap);
    const double next = std::clamp(wanted, force_command_n_[c] - step_n, force_command_n_[c] + step_n);
    if (next != force_target_n_[c]) flags |= transport::kLimitForce;
    force_command_n_[c] = next;
  }
  return flags;
}

void ServoNodeController::leave_force_control() {
  // The safe state of a force channel: displacement control, holding where the piston is.
  for (int c = 0; c < config_.channels; ++c) {
    if (mode_[c] != servo::ControlMode::kForce) continue;
    mode_[c] = servo::ControlMode::kDisplacement;
    target_m_[c] = command_m_[c] = reading_.displacement_m[c];
    change_m_[c] = 0.0;
  }
}

template <int N>
inline void ServoNodeController::tick_n(transport::FeedbackSample& out) {
  const int channels = count<N>();
  out.test_id = config_.test_id;
  out.site_id = config_.site_id;
  out.run_id = run_id_;
  out.channels = static_cast<std::uint8_t>(channels);
  if (!started_) {
    out.step = -1;
    out.time_s = 0.0;
    out.status = transport::kNodeFault;
    out.limit_flags = transport::kLimitNone;
    return;
  }

  const bool faulted_before = fault_;
  choose_target<N>();
  // A force channel enters force control with its first command, from the force it measures.
  if (any_force_channel_ && commands_began_ && !fault_ && !safe_state_) {
    for (int c = 0; c < channels; ++c) {
      if (config_.control[c] != servo::ControlMode::kForce || mode_[c] == servo::ControlMode::kForce) continue;
      mode_[c] = servo::ControlMode::kForce;
      force_command_n_[c] = reading_.force_n[c];
    }
  }
  Values applied;  // apply_limits sets each channel's; the rest is never read
  std::uint32_t flags = apply_limits<N>(applied);
  servo::ActuatorStatus status = servo::ActuatorStatus::kOk;
  const auto n = static_cast<std::size_t>(channels);
  if (any_force_channel_) {
    flags |= apply_force_limits();
    // A fault or the safe state: displacement control at the measured position, which
    // apply_limits has already made a force channel's applied command.
    if (fault_ || safe_state_) leave_force_control();
    status = actuator_.exchange_mixed(
        std::span<const double>(applied.data(), n), std::span<const double>(force_command_n_.data(), n),
        std::span<const servo::ControlMode>(mode_.data(), n), config_.control_period_s, reading_);
  } else {
    // Displacement only: the path every existing node file takes, unchanged.
    status = actuator_.exchange(std::span<const double>(applied.data(), n), config_.control_period_s, reading_);
  }
  for (int c = 0; c < channels; ++c) {
    change_m_[c] = applied[c] - command_m_[c];
    command_m_[c] = applied[c];
  }
  if (status == servo::ActuatorStatus::kOk) {
    keep_latest_measurement<N>();
    has_measurement_ = true;
  }
  if (status == servo::ActuatorStatus::kNoReply) ++counters_.actuator_no_replies;
  if (status == servo::ActuatorStatus::kFault) {
    ++counters_.actuator_faults;
    latch_fault();
    if (!faulted_before) keep_fault_text(actuator_.fault_text());
  }
  // A new measurement faults the node on this tick's feedback if no measurement may be where it is.
  if (status == servo::ActuatorStatus::kOk) flags |= check_measurement<N>();
  if (fault_ && !faulted_before && fault_text_[0] == '\0' && !events_.empty() && events_not_logged_ == 0)
    describe_fault(events_.back());
  ++counters_.ticks;
  ++ticks_since_accepted_;

  out.step = followed_step_;
  out.time_s = followed_time_s_;
  // 0 beyond the channels: whole arrays cleared (a few wide stores), then the channels'.
  out.displacement_m = {};
  out.force_n = {};
  for (int c = 0; c < channels; ++c) {
    out.displacement_m[c] = reading_.displacement_m[c];
    out.force_n[c] = reading_.force_n[c];
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

// Inline: once a tick, from tick_n() alone (this file).
template <int N>
inline void ServoNodeController::keep_latest_measurement() {
  // The node's channels and the flags: what a heartbeat reads of it.
  for (int c = 0; c < count<N>(); ++c) {
    latest_measurement_.displacement_m[c] = reading_.displacement_m[c];
    latest_measurement_.force_n[c] = reading_.force_n[c];
  }
  latest_measurement_.fresh = reading_.fresh;
  latest_measurement_.at_end_stop = reading_.at_end_stop;
  latest_measurement_.valve_saturated = reading_.valve_saturated;
}

template <int N>
bool ServoNodeController::answer_n(const transport::CommandSample& command, transport::FeedbackSample& feedback) {
  if (accept_n<N>(command) != CommandVerdict::kAccepted) return false;
  tick_n<N>(feedback);
  return true;
}

template <int N>
constexpr ServoNodeController::Steps ServoNodeController::steps_of() {
  return {&ServoNodeController::accept_n<N>, &ServoNodeController::tick_n<N>, &ServoNodeController::answer_n<N>};
}

void ServoNodeController::keep_fault_text(std::string_view text) noexcept {
  const std::size_t n = std::min(text.size(), fault_text_.size() - 1);
  std::copy_n(text.data(), n, fault_text_.begin());
  fault_text_[n] = '\0';
}

void ServoNodeController::describe_fault(const LimitEvent& e) noexcept {
  // snprintf into a fixed buffer: no allocation on the control path.
  std::snprintf(fault_text_.data(), fault_text_.size(), "%s %s on channel %d: %g beyond %g", limit_kind_name(e.kind),
                limit_cause_name(e.cause), e.channel, e.observed, e.bound);
}

}  // namespace rpsd::node
