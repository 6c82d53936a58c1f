#include "rpsd/coordinator/experimental_exchange.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {

namespace {

std::array<char, 64> label(const std::string& text) {
  std::array<char, 64> out{};
  std::snprintf(out.data(), out.size(), "%s", text.c_str());
  return out;
}

}  // namespace

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
  link_channels_ = channels_ + static_cast<int>(parts_.held_forces.size());
  if (link_channels_ > transport::kMaxChannels) {
    throw std::invalid_argument("ExperimentalExchange: " + std::to_string(link_channels_) +
                                " link channels with the held forces, at most " +
                                std::to_string(transport::kMaxChannels));
  }
  for (std::size_t k = 0; k < parts_.held_forces.size(); ++k) {
    const HeldForceChannel& h = parts_.held_forces[k];
    if (h.channel != channels_ + static_cast<int>(k)) {
      throw std::invalid_argument("ExperimentalExchange: held force " + std::to_string(k) +
                                  " must be on link channel " + std::to_string(channels_ + static_cast<int>(k)));
    }
    if (!(h.max_force_rate_n_per_s > 0.0) || !std::isfinite(h.force_n) || !std::isfinite(h.force_at_rest_n)) {
      throw std::invalid_argument(std::string("ExperimentalExchange: ") + h.name.data() +
                                  ": a finite force, a force at rest and a rate > 0 are required");
    }
    command_.control_mode[static_cast<std::size_t>(h.channel)] = transport::kForceControl;
  }
  command_.channels = static_cast<std::uint8_t>(link_channels_);
  group_of_.fill(-1);
  index_in_group_.fill(-1);
  groups_.reserve(parts_.setups.size());
  for (const SetupGroup& sg : parts_.setups) {
    const std::string site = "site " + std::to_string(sg.site_id);
    Group g(sg, setups::PlanarSetup(sg.geometry));  // checks the geometry
    g.name = label(site + " setup");
    const int n = g.setup.dofs();
    if (static_cast<int>(sg.channels.size()) != n) {
      throw std::invalid_argument("ExperimentalExchange: " + site + "'s setup drives " + std::to_string(n) +
                                  " DOFs on " + std::to_string(sg.channels.size()) + " channels");
    }
    if (!sg.actuator_limits.empty() && static_cast<int>(sg.actuator_limits.size()) != n) {
      throw std::invalid_argument("ExperimentalExchange: " + site + ": limits for every actuator or for none");
    }
    if (!sg.calibration_offset_m.empty() && static_cast<int>(sg.calibration_offset_m.size()) != n) {
      throw std::invalid_argument("ExperimentalExchange: " + site +
                                  ": a calibration offset for every actuator or none");
    }
    for (int i = 0; i < n; ++i) {
      const int c = sg.channels[static_cast<std::size_t>(i)];
      if (c < 0 || c >= channels_ || group_of_[static_cast<std::size_t>(c)] >= 0) {
        throw std::invalid_argument("ExperimentalExchange: " + site + "'s setup names channel " + std::to_string(c) +
                                    ", which is not a channel of the test or is another setup's");
      }
      group_of_[static_cast<std::size_t>(c)] = static_cast<int>(groups_.size());
      index_in_group_[static_cast<std::size_t>(c)] = i;
      const setups::PlanarActuator& a = sg.geometry.actuators[static_cast<std::size_t>(i)];
      g.actuator_names.push_back(label(site + " actuator " + (a.name.empty() ? std::to_string(i + 1) : a.name)));
      const setups::DofMotion motion = sg.geometry.dofs[static_cast<std::size_t>(i)];
      g.dof_names.push_back(
          label(site + " DOF " + std::string(setups::dof_motion_name(motion))));  // one motion per setup DOF
      const bool rotation = motion == setups::DofMotion::kRotation;
      g.dof_units.push_back(rotation ? "rad" : "m");
      g.dof_force_units.push_back(rotation ? "N·m" : "N");
    }
    for (auto* v : {&g.dof_target, &g.dof_command, &g.stroke_target, &g.stroke_command, &g.stroke_measured,
                    &g.dof_measured, &g.actuator_force, &g.dof_force, &g.offset, &g.last_dof_command}) {
      *v = setups::SetupVector::Zero(n);
    }
    for (int i = 0; i < n && !sg.calibration_offset_m.empty(); ++i) {
      g.offset[i] = sg.calibration_offset_m[static_cast<std::size_t>(i)];
    }
    groups_.push_back(std::move(g));
  }
  for (int c = 0; c < channels_; ++c) {
    compensator_calls_[static_cast<std::size_t>(c)] = compensation::CompensatorCall(parts_.compensators[c]);
  }
  one_plain_channel_ = channels_ == 1 && groups_.empty() && parts_.held_forces.empty();
}

void ExperimentalExchange::start(const Eigen::VectorXd& targets, std::span<const double> specimen_force_n) {
  if (targets.size() != channels_ || static_cast<int>(specimen_force_n.size()) != channels_) {
    throw std::invalid_argument("ExperimentalExchange::start: one target and one force per channel");
  }
  targets_ = targets;
  for (int c = 0; c < channels_; ++c) {
    if (group_of_[static_cast<std::size_t>(c)] >= 0) continue;
    parts_.compensators[c]->reset(targets_[c]);
    tracking_[c].reset(targets_[c], targets_[c]);
    specimen_forces_[c] = specimen_force_n[c];
    last_sent_m_[c] = targets_[c];  // the actuator holds the start
  }
  // A setup's actuators hold the strokes of its DOFs' start, read with their offsets.
  for (Group& g : groups_) {
    const int n = g.setup.dofs();
    for (int i = 0; i < n; ++i) g.dof_target[i] = targets_[g.parts.channels[static_cast<std::size_t>(i)]];
    g.setup.strokes(g.dof_target, g.stroke_target);
    g.dof_command = g.last_dof_command = g.dof_measured = g.dof_target;
    g.stroke_command = g.stroke_measured = g.stroke_target;
    for (int i = 0; i < n; ++i) {
      const int c = g.parts.channels[static_cast<std::size_t>(i)];
      parts_.compensators[c]->reset(g.parts.compensate_dofs ? g.dof_target[i] : g.stroke_target[i]);
      tracking_[c].reset(g.stroke_target[i], g.stroke_target[i]);
      specimen_forces_[c] = specimen_force_n[c];
      g.dof_force[i] = specimen_force_n[c];
      last_sent_m_[c] = g.stroke_target[i] + g.offset[i];
    }
    g.actuator_force.setZero();
    // Best effort at rest: the actuators' forces that carry the DOFs' (a singular start was
    // refused when the setup was made).
    (void)g.setup.actuator_forces(g.dof_target, g.dof_force, g.actuator_force);
  }
  for (const HeldForceChannel& h : parts_.held_forces) {
    const auto c = static_cast<std::size_t>(h.channel);
    command_.force_n[c] = h.force_at_rest_n;  // the node enters force control from what it measures
    command_.displacement_m[c] = 0.0;         // not followed in force control
    feedback_.force_n[c] = h.force_at_rest_n;
  }
  limit_stop_ = LimitStop{};
  saturated_exchanges_ = 0;
  exchange_ = 0;
  late_total_ = 0;
  feedback_age_ = 0;
  feedback_.step = -1;
}

void ExperimentalExchange::stop_on_actuator(const Group& g, int i, LimitStop::Kind kind, double value, double bound) {
  limit_stop_ = {kind, g.parts.channels[static_cast<std::size_t>(i)], value, bound};
  limit_stop_.setup = static_cast<int>(&g - groups_.data());
  limit_stop_.actuator = i;
  limit_stop_.name = g.actuator_names[static_cast<std::size_t>(i)];
  limit_stop_.unit = kind == LimitStop::Kind::kForce ? "N" : "m";
}

void ExperimentalExchange::stop_on_dof(const Group& g, int i, LimitStop::Kind kind, double value, double bound,
                                       bool force) {
  limit_stop_ = {kind, g.parts.channels[static_cast<std::size_t>(i)], value, bound};
  limit_stop_.setup = static_cast<int>(&g - groups_.data());
  limit_stop_.dof = i;
  limit_stop_.name = g.dof_names[static_cast<std::size_t>(i)];
  limit_stop_.unit = force ? g.dof_force_units[static_cast<std::size_t>(i)] : g.dof_units[static_cast<std::size_t>(i)];
}

// The exchange of N channels (kAnyChannels: as many as the test has) and its parts that loop
// over the channels. The constructor picks N = 1 for a test of one channel without setups or
// held forces: there every loop has one entry and every setup and held-force branch is known
// to be empty when it is compiled. Each is called from exchange() alone, once an exchange.
template <int N>
int ExperimentalExchange::channel_count() const {
  if constexpr (N == kAnyChannels) {
    return channels_;
  } else {
    return N;
  }
}

template <int N>
bool ExperimentalExchange::in_setup(int c) const {
  if constexpr (N == kAnyChannels) {
    return group_of_[static_cast<std::size_t>(c)] >= 0;
  } else {
    return false;
  }
}

template <int N>
std::span<ExperimentalExchange::Group> ExperimentalExchange::setup_groups() {
  if constexpr (N == kAnyChannels) {
    return groups_;
  } else {
    return {};
  }
}

template <int N>
bool ExperimentalExchange::holds_forces() const {
  if constexpr (N == kAnyChannels) {
    return !parts_.held_forces.empty();
  } else {
    return false;
  }
}

template <int N>
bool ExperimentalExchange::commands_within_limits() {
  // In the order the stop names the first limit that acts: held forces, setups, channels.
  if ((holds_forces<N>() || !setup_groups<N>().empty()) && !held_and_setup_commands_within_limits()) return false;
  if (parts_.limits.empty()) return true;
  const CoordinatorLimits* const limits = parts_.limits.data();
  for (int c = 0; c < channel_count<N>(); ++c) {
    if (in_setup<N>(c)) continue;
    const CoordinatorLimits& l = limits[c];
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

bool ExperimentalExchange::held_and_setup_commands_within_limits() {
  // A held force's command (the ramp from its force at rest) is never sent beyond its force limit.
  for (int k = 0; k < static_cast<int>(parts_.held_forces.size()); ++k) {
    const HeldForceChannel& h = parts_.held_forces[static_cast<std::size_t>(k)];
    const double f = command_.force_n[static_cast<std::size_t>(h.channel)];
    if (std::abs(f) > h.limits.max_force_n) {
      stop_on_held(k, LimitStop::Kind::kForce, f, h.limits.max_force_n, "N");
      return false;
    }
  }
  // A setup's actuators: on the stroke as sent (what the hardware sees), then its DOFs' own
  // limits on the DOFs' commands.
  for (Group& g : groups_) {
    const int n = g.setup.dofs();
    for (int i = 0; i < n && !g.parts.actuator_limits.empty(); ++i) {
      const CoordinatorLimits& l = g.parts.actuator_limits[static_cast<std::size_t>(i)];
      const int c = g.parts.channels[static_cast<std::size_t>(i)];
      const double x = command_.displacement_m[c], change = x - last_sent_m_[c];
      if (!std::isfinite(x) || std::abs(x) > l.max_stroke_m) {
        stop_on_actuator(g, i, LimitStop::Kind::kStroke, x, l.max_stroke_m);
        return false;
      }
      if (std::abs(change) > l.max_increment_m) {
        stop_on_actuator(g, i, LimitStop::Kind::kIncrement, change, l.max_increment_m);
        return false;
      }
    }
    for (int i = 0; i < n && !parts_.limits.empty(); ++i) {
      const CoordinatorLimits& l = parts_.limits[g.parts.channels[static_cast<std::size_t>(i)]];
      const double u = g.dof_command[i], change = u - g.last_dof_command[i];
      if (!std::isfinite(u) || std::abs(u) > l.max_stroke_m) {
        stop_on_dof(g, i, LimitStop::Kind::kStroke, u, l.max_stroke_m, false);
        return false;
      }
      if (std::abs(change) > l.max_increment_m) {
        stop_on_dof(g, i, LimitStop::Kind::kIncrement, change, l.max_increment_m, false);
        return false;
      }
    }
  }
  return true;
}

template <int N>
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
  if (!setup_groups<N>().empty()) {
    if (const StepOutcome outcome = setup_run_away(); outcome != StepOutcome::kOk) return outcome;
  }
  if (!parts_.limits.empty()) {
    const CoordinatorLimits* const limits = parts_.limits.data();
    for (int c = 0; c < channel_count<N>(); ++c) {
      if (in_setup<N>(c)) continue;
      const double error = targets_[c] - feedback_.displacement_m[c];
      if (std::abs(error) > limits[c].max_tracking_error_m) {
        limit_stop_ = {LimitStop::Kind::kTrackingError, c, error, limits[c].max_tracking_error_m};
        return StepOutcome::kRunAway;
      }
    }
  }
  return StepOutcome::kOk;
}

StepOutcome ExperimentalExchange::setup_run_away() {
  // A setup's actuators: the error of each actuator's own stroke.
  for (Group& g : groups_) {
    for (int i = 0; i < g.setup.dofs() && !g.parts.actuator_limits.empty(); ++i) {
      const int c = g.parts.channels[static_cast<std::size_t>(i)];
      const double error = g.stroke_target[i] + g.offset[i] - feedback_.displacement_m[c];
      const double bound = g.parts.actuator_limits[static_cast<std::size_t>(i)].max_tracking_error_m;
      if (std::abs(error) > bound) {
        stop_on_actuator(g, i, LimitStop::Kind::kTrackingError, error, bound);
        return StepOutcome::kRunAway;
      }
    }
  }
  return StepOutcome::kOk;
}

StepOutcome ExperimentalExchange::exchange(const Eigen::VectorXd& targets, double time_s) {
  return one_plain_channel_ ? exchange_of<1>(targets, time_s) : exchange_of<kAnyChannels>(targets, time_s);
}

template <int N>
StepOutcome ExperimentalExchange::exchange_of(const Eigen::VectorXd& targets, double time_s) {
  // The vectors' storage held in locals: a compensator's virtual call could change any member
  // for all the compiler knows, and it would load them again.
  double* const target = targets_.data();
  compensation::CompensatorCall* const compensators = compensator_calls_.data();
  command_.step = exchange_;
  command_.time_s = time_s;
  for (int c = 0; c < channel_count<N>(); ++c) {
    const double t = targets[c];
    target[c] = t;
    if (!in_setup<N>(c)) command_.displacement_m[c] = compensated_ ? compensators[c].command(t) : t;
  }
  for (Group& g : setup_groups<N>()) command_setup(g);
  if (holds_forces<N>()) command_held_forces(time_s);
  if (!commands_within_limits<N>()) return StepOutcome::kLimit;
  if (parts_.link->send(command_) != transport::LinkStatus::kOk) return StepOutcome::kLinkFailure;
  for (int c = 0; c < channel_count<N>(); ++c) last_sent_m_[c] = command_.displacement_m[c];
  for (Group& g : setup_groups<N>()) g.last_dof_command = g.dof_command;
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
  // The link's channels: the structure's and the held forces' (none where N is fixed).
  const int link_channels = N == kAnyChannels ? link_channels_ : N;
  if (transport::has_non_finite_measurement(feedback_, link_channels)) return StepOutcome::kNonFinite;
  if (const StepOutcome outcome = run_away<N>(); outcome != StepOutcome::kOk) return outcome;
  if (holds_forces<N>()) {
    if (const StepOutcome outcome = check_held_forces(); outcome != StepOutcome::kOk) return outcome;
  }
  const CoordinatorLimits* const limits = parts_.limits.empty() ? nullptr : parts_.limits.data();
  compensation::TrackingIndicator* const tracking = tracking_.data();
  for (int c = 0; c < channel_count<N>(); ++c) {
    if (in_setup<N>(c)) {
      // A setup's actuator: its load cell against its own force limit, its stroke tracked.
      Group& group = groups_[static_cast<std::size_t>(group_of_[static_cast<std::size_t>(c)])];
      const int i = index_in_group_[static_cast<std::size_t>(c)];
      const std::vector<CoordinatorLimits>& l = group.parts.actuator_limits;
      if (!l.empty() && std::abs(feedback_.force_n[c]) > l[static_cast<std::size_t>(i)].max_force_n) {
        stop_on_actuator(group, i, LimitStop::Kind::kForce, feedback_.force_n[c],
                         l[static_cast<std::size_t>(i)].max_force_n);
        return StepOutcome::kLimit;
      }
      group.stroke_measured[i] = feedback_.displacement_m[c] - group.offset[i];
      group.actuator_force[i] = feedback_.force_n[c];
      if (!group.parts.compensate_dofs) compensators[c].observe(group.stroke_target[i], group.stroke_measured[i]);
      tracking[c].update(group.stroke_target[i], group.stroke_measured[i]);
      continue;
    }
    const double force = feedback_.force_n[c], measured = feedback_.displacement_m[c];
    if (limits && std::abs(force) > limits[c].max_force_n) {
      limit_stop_ = {LimitStop::Kind::kForce, c, force, limits[c].max_force_n};
      return StepOutcome::kLimit;
    }
    compensators[c].observe(target[c], measured);
    tracking[c].update(target[c], measured);
  }
  for (Group& g : setup_groups<N>()) {
    if (const StepOutcome outcome = feedback_setup(g); outcome != StepOutcome::kOk) return outcome;
  }
  const RestoringForcePath* const paths = parts_.force_paths.data();
  double* const specimen_force = specimen_forces_.data();
  for (int c = 0; c < channel_count<N>(); ++c) {
    if (in_setup<N>(c)) continue;
    specimen_force[c] = paths[c].source == RestoringForceSource::kMeasuredForce
                            ? feedback_.force_n[c]
                            : paths[c].stiffness_n_per_m * feedback_.displacement_m[c];
  }
  return StepOutcome::kOk;
}

void ExperimentalExchange::command_held_forces(double time_s) {
  // The ramp follows test time, so a late cycle in real time does not slow it.
  for (const HeldForceChannel& h : parts_.held_forces) {
    const double to_go = h.force_n - h.force_at_rest_n;
    const double ramped = h.max_force_rate_n_per_s * std::max(0.0, time_s);
    command_.force_n[static_cast<std::size_t>(h.channel)] =
        std::abs(to_go) <= ramped ? h.force_n : h.force_at_rest_n + std::copysign(ramped, to_go);
  }
}

void ExperimentalExchange::stop_on_held(int k, LimitStop::Kind kind, double value, double bound, const char* unit) {
  const HeldForceChannel& h = parts_.held_forces[static_cast<std::size_t>(k)];
  limit_stop_ = {kind, h.channel, value, bound};
  limit_stop_.held = k;
  limit_stop_.name = h.name;
  limit_stop_.unit = unit;
}

StepOutcome ExperimentalExchange::check_held_forces() {
  for (int k = 0; k < static_cast<int>(parts_.held_forces.size()); ++k) {
    const HeldForceChannel& h = parts_.held_forces[static_cast<std::size_t>(k)];
    const auto c = static_cast<std::size_t>(h.channel);
    const double force = feedback_.force_n[c], stroke = feedback_.displacement_m[c];
    if (std::abs(force) > h.limits.max_force_n) {
      stop_on_held(k, LimitStop::Kind::kForce, force, h.limits.max_force_n, "N");
      return StepOutcome::kLimit;
    }
    // A specimen that softens lets a piston in force control run: its stroke is the check.
    if (std::abs(stroke) > h.limits.max_stroke_m) {
      stop_on_held(k, LimitStop::Kind::kStroke, stroke, h.limits.max_stroke_m, "m");
      return StepOutcome::kRunAway;
    }
    const double error = command_.force_n[c] - force;
    if (std::abs(error) > h.limits.max_force_error_n) {
      stop_on_held(k, LimitStop::Kind::kTrackingError, error, h.limits.max_force_error_n, "N");
      return StepOutcome::kRunAway;
    }
  }
  return StepOutcome::kOk;
}

double ExperimentalExchange::command_in_target_space(int c) const {
  const int g = group_of_[static_cast<std::size_t>(c)];
  if (g < 0) return command_.displacement_m[static_cast<std::size_t>(c)];
  const Group& group = groups_[static_cast<std::size_t>(g)];
  return group.parts.compensate_dofs ? group.dof_command[index_in_group_[static_cast<std::size_t>(c)]] : targets_[c];
}

void ExperimentalExchange::command_setup(Group& g) {
  const int n = g.setup.dofs();
  for (int i = 0; i < n; ++i) {
    const int c = g.parts.channels[static_cast<std::size_t>(i)];
    g.dof_target[i] = targets_[c];
    g.dof_command[i] =
        g.parts.compensate_dofs && compensated_ ? parts_.compensators[c]->command(targets_[c]) : targets_[c];
  }
  g.setup.strokes(g.dof_target, g.stroke_target);
  if (g.parts.compensate_dofs) {
    g.setup.strokes(g.dof_command, g.stroke_command);
  } else {
    for (int i = 0; i < n; ++i) {
      g.stroke_command[i] =
          compensated_ ? parts_.compensators[g.parts.channels[static_cast<std::size_t>(i)]]->command(g.stroke_target[i])
                       : g.stroke_target[i];
    }
  }
  for (int i = 0; i < n; ++i) {
    command_.displacement_m[g.parts.channels[static_cast<std::size_t>(i)]] = g.stroke_command[i] + g.offset[i];
  }
}

StepOutcome ExperimentalExchange::feedback_setup(Group& g) {
  const int n = g.setup.dofs();
  // Newton from the last solution: the specimen moves little in one control period.
  const setups::SetupVector guess = g.dof_measured;
  const setups::SetupStatus status = g.setup.displacements(g.stroke_measured, guess, g.dof_measured);
  if (status != setups::SetupStatus::kOk) {
    g.dof_measured = guess;
    limit_stop_ = {LimitStop::Kind::kGeometry, g.parts.channels.front(), static_cast<double>(status), 0.0};
    limit_stop_.setup = static_cast<int>(&g - groups_.data());
    limit_stop_.name = g.name;
    return StepOutcome::kGeometry;
  }
  g.setup.dof_forces(g.dof_measured, g.actuator_force, g.dof_force);
  for (int i = 0; i < n && !parts_.limits.empty(); ++i) {
    const CoordinatorLimits& l = parts_.limits[g.parts.channels[static_cast<std::size_t>(i)]];
    if (std::abs(g.dof_force[i]) > l.max_force_n) {
      stop_on_dof(g, i, LimitStop::Kind::kForce, g.dof_force[i], l.max_force_n, true);
      return StepOutcome::kLimit;
    }
    const double error = g.dof_target[i] - g.dof_measured[i];
    if (std::abs(error) > l.max_tracking_error_m) {
      stop_on_dof(g, i, LimitStop::Kind::kTrackingError, error, l.max_tracking_error_m, false);
      return StepOutcome::kRunAway;
    }
  }
  for (int i = 0; i < n; ++i) {
    const int c = g.parts.channels[static_cast<std::size_t>(i)];
    if (g.parts.compensate_dofs) parts_.compensators[c]->observe(g.dof_target[i], g.dof_measured[i]);
    const RestoringForcePath& path = parts_.force_paths[c];
    specimen_forces_[c] = path.source == RestoringForceSource::kMeasuredForce
                              ? g.dof_force[i]
                              : path.stiffness_n_per_m * g.dof_measured[i];
  }
  return StepOutcome::kOk;
}

// Inline into each fill_channels: the loop's row is written in the call it makes.
template <typename Out>
[[gnu::always_inline]] inline void ExperimentalExchange::write_channels(Out out) const {
  // Each value read once into a local: a store into the record could alias the vectors' storage
  // for all the compiler knows, and it would read them again.
  const double *target = targets_.data(), *specimen_force = specimen_forces_.data();
  const compensation::TrackingIndicator* const tracking = tracking_.data();
  for (int c = 0; c < channels_; ++c) {
    const double t = target[c], x = feedback_.displacement_m[c], f = feedback_.force_n[c];
    RecordLayout::Channel v{
        t, command_.displacement_m[c], x, f, specimen_force[c], tracking[c].value_m2(), t, x, f, round_trip_s(c)};
    // A setup's channel: the actuator's strokes (offsets off) beside its DOF's view.
    if (const int g = group_of_[static_cast<std::size_t>(c)]; g >= 0) {
      const Group& group = groups_[static_cast<std::size_t>(g)];
      const int i = index_in_group_[static_cast<std::size_t>(c)];
      v.target_m = group.stroke_target[i];
      v.command_m = group.stroke_command[i];
      v.measured_m = group.stroke_measured[i];
      v.dof_target_m = group.dof_target[i];
      v.dof_measured_m = group.dof_measured[i];
      v.dof_force_n = group.dof_force[i];
    }
    out.channel(c, v);
  }
  const int held = link_channels_ - channels_;  // the held forces follow the channels
  for (int k = 0; k < held; ++k) {
    const auto c = static_cast<std::size_t>(parts_.held_forces[static_cast<std::size_t>(k)].channel);
    out.held(k, command_.force_n[c], feedback_.displacement_m[c], feedback_.force_n[c]);
  }
  out.channels(static_cast<std::uint8_t>(channels_), static_cast<std::uint8_t>(held), feedback_.status,
               feedback_.limit_flags);
}

void ExperimentalExchange::fill_channels(StepRecord& r) const { write_channels(RecordChannels(r)); }

void ExperimentalExchange::fill_channels(RecordLayout::Row row) const { write_channels(row); }

}  // namespace rpsd::coordinator
