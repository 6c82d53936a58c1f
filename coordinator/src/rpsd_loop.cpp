#include "rpsd/coordinator/rpsd_loop.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {

RpsdLoop::RpsdLoop(LoopParts parts) : parts_(std::move(parts)) {
  if (!parts_.integrator || !parts_.numerical || !parts_.partition || !parts_.link) {
    throw std::invalid_argument("RpsdLoop: integrator, numerical model, partition and link are all required");
  }
  dofs_ = parts_.numerical->dofs();
  channels_ = static_cast<int>(parts_.partition->channels());
  if (parts_.integrator->size() != dofs_ || parts_.partition->dofs() != dofs_) {
    throw std::invalid_argument("RpsdLoop: the integrator, numerical model and partition have different DOF counts");
  }
  if (channels_ < 1 || channels_ > transport::kMaxChannels) {
    throw std::invalid_argument("RpsdLoop: between 1 and " + std::to_string(transport::kMaxChannels) +
                                " actuator channels");
  }
  if (static_cast<int>(parts_.compensators.size()) != channels_ ||
      static_cast<int>(parts_.force_paths.size()) != channels_) {
    throw std::invalid_argument("RpsdLoop: one compensator and one restoring-force path per actuator channel");
  }
  for (auto* c : parts_.compensators) {
    if (!c) throw std::invalid_argument("RpsdLoop: null compensator (use the pass-through one)");
  }
  if (static_cast<int>(parts_.recorded_dofs.size()) > kMaxRecordedDofs) {
    throw std::invalid_argument("RpsdLoop: at most " + std::to_string(kMaxRecordedDofs) + " recorded DOFs");
  }
  for (Eigen::Index dof : parts_.recorded_dofs) {
    if (dof < 0 || dof >= dofs_)
      throw std::invalid_argument("RpsdLoop: recorded DOF " + std::to_string(dof) + " out of range");
  }
  if (!parts_.limits.empty() && static_cast<int>(parts_.limits.size()) != channels_) {
    throw std::invalid_argument("RpsdLoop: limits for every actuator channel or for none");
  }
  if (!parts_.ground_acceleration_m_per_s2.empty() && parts_.ground_load == nullptr) {
    throw std::invalid_argument("RpsdLoop: a ground-motion record needs the ground-motion load (M iota)");
  }
  for (auto* v : {&force_, &restoring_, &previous_d_, &previous_v_, &previous_r_, &previous_f_, &work_a_, &work_b_}) {
    *v = Eigen::VectorXd::Zero(dofs_);
  }
  targets_ = Eigen::VectorXd::Zero(channels_);
  specimen_forces_ = Eigen::VectorXd::Zero(channels_);
  tracking_.resize(channels_);
  command_.test_id = feedback_.test_id = parts_.test_id;
  command_.run_id = parts_.run_id != 0 ? parts_.run_id : transport::draw_run_id();
  command_.channels = static_cast<std::uint8_t>(channels_);
}

const char* limit_stop_name(LimitStop::Kind kind) {
  switch (kind) {
    case LimitStop::Kind::kNone:
      return "none";
    case LimitStop::Kind::kStroke:
      return "max_stroke_m";
    case LimitStop::Kind::kIncrement:
      return "max_increment_m";
    case LimitStop::Kind::kForce:
      return "max_force_n";
    case LimitStop::Kind::kTrackingError:
      return "max_tracking_error_m";
    case LimitStop::Kind::kNodeLimit:
      return "node_limit";
    case LimitStop::Kind::kEndStop:
      return "end_stop";
    case LimitStop::Kind::kValveSaturation:
      return "valve_saturation";
  }
  return "unknown";
}

std::int64_t RpsdLoop::steps_available() const {
  const auto n = static_cast<std::int64_t>(parts_.ground_acceleration_m_per_s2.size());
  return n == 0 ? -1 : n - 1;
}

void RpsdLoop::start(const Eigen::VectorXd& d0, std::span<const double> specimen_force0_n) {
  if (d0.size() != dofs_ || static_cast<int>(specimen_force0_n.size()) != channels_) {
    throw std::invalid_argument("RpsdLoop::start: d0 needs one value per DOF and one force per channel");
  }
  parts_.partition->extract_commands(d0, targets_);
  for (int c = 0; c < channels_; ++c) {
    parts_.compensators[c]->reset(targets_[c]);
    tracking_[c].reset(targets_[c], targets_[c]);
    specimen_forces_[c] = specimen_force0_n[c];
    last_sent_m_[c] = targets_[c];  // the actuator holds the start
  }
  limit_stop_ = LimitStop{};
  saturated_exchanges_ = 0;
  parts_.numerical->restoring_force(d0, restoring_);
  parts_.partition->add_forces(specimen_forces_, restoring_);
  parts_.numerical->commit();
  force_.setZero();
  if (parts_.ground_load && !parts_.ground_acceleration_m_per_s2.empty()) {
    parts_.ground_load->force(parts_.ground_acceleration_m_per_s2[0], force_);
  }
  parts_.integrator->initialize(d0, Eigen::VectorXd::Zero(dofs_), restoring_, force_);
  step_ = 0;
  exchange_ = 0;
  record_ = StepRecord{};
  late_total_ = 0;
  feedback_age_ = 0;
  feedback_.step = -1;
  previous_d_ = d0;
  previous_v_.setZero();
  previous_r_ = restoring_;
  previous_f_ = force_;
  input_energy_j_ = damping_energy_j_ = restoring_energy_j_ = kinetic_energy_j_ = 0.0;
}

bool RpsdLoop::commands_within_limits() {
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

StepOutcome RpsdLoop::run_away() {
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

void RpsdLoop::experimental_forces(const transport::FeedbackSample& feedback) {
  for (int c = 0; c < channels_; ++c) {
    const RestoringForcePath& path = parts_.force_paths[c];
    specimen_forces_[c] = path.source == RestoringForceSource::kMeasuredForce
                              ? feedback.force_n[c]
                              : path.stiffness_n_per_m * feedback.displacement_m[c];
  }
}

StepOutcome RpsdLoop::step(Recorder& recorder) {
  const std::int64_t available = steps_available();
  if (available >= 0 && step_ >= available) return StepOutcome::kRecordEnded;
  auto& integrator = *parts_.integrator;
  auto& numerical = *parts_.numerical;
  const auto& partition = *parts_.partition;

  const double ground = available >= 0 ? parts_.ground_acceleration_m_per_s2[step_ + 1] : 0.0;
  if (available >= 0) parts_.ground_load->force(ground, force_);
  if (integrator.begin_step(force_) != integrators::StepStatus::kOk) return StepOutcome::kIntegratorError;

  const int iterations = integrator.iterations_per_step();
  oldest_age_this_step_ = 0;
  for (int it = 0; it < iterations; ++it) {
    const Eigen::VectorXd& d = integrator.target_displacement();
    partition.extract_commands(d, targets_);
    command_.step = exchange_;
    command_.time_s = (exchange_ + 1) * integrator.dt_s() / iterations;
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
      oldest_age_this_step_ = std::max(oldest_age_this_step_, feedback_age_);
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
    experimental_forces(feedback_);
    numerical.restoring_force(d, restoring_);
    partition.add_forces(specimen_forces_, restoring_);
    if (integrator.set_measured_restoring_force(restoring_) != integrators::StepStatus::kOk) {
      return StepOutcome::kIntegratorError;
    }
  }
  if (integrator.end_step() != integrators::StepStatus::kOk) return StepOutcome::kIntegratorError;
  numerical.commit();
  ++step_;

  // Energy balance by the trapezoidal rule over the step (model scale):
  // input = sum F.dd, damping = sum (Cv).dd, restoring = sum R.dd, kinetic = 1/2 v'Mv.
  const Eigen::VectorXd& d = integrator.displacement();
  const Eigen::VectorXd& v = integrator.velocity();
  const Eigen::VectorXd& r = integrator.restoring_force();
  work_a_ = d - previous_d_;
  input_energy_j_ += 0.5 * (previous_f_ + force_).dot(work_a_);
  restoring_energy_j_ += 0.5 * (previous_r_ + r).dot(work_a_);
  work_b_ = v + previous_v_;
  numerical.damping().multiply(work_b_, restoring_);  // restoring_ reused as scratch: C (v + v_prev)
  damping_energy_j_ += 0.5 * restoring_.dot(work_a_);
  numerical.mass().multiply(v, work_b_);
  kinetic_energy_j_ = 0.5 * v.dot(work_b_);
  previous_d_ = d;
  previous_v_ = v;
  previous_r_ = r;
  previous_f_ = force_;

  record_.step = step_;
  record_.time_s = integrator.time_s();
  record_.ground_acceleration_m_per_s2 = ground;
  fill_record(record_);
  record_.node_status = feedback_.status;
  record_.limit_flags = feedback_.limit_flags;
  record_.cycle_lateness_s = static_cast<double>(cycle_lateness_ns_) * 1e-9;
  record_.feedback_age_periods = static_cast<std::uint8_t>(std::min<std::int64_t>(oldest_age_this_step_, 255));
  if (parts_.wait_for_recorder) {
    recorder.record_or_wait(record_);
  } else {
    recorder.record(record_);
  }
  return StepOutcome::kOk;
}

void RpsdLoop::fill_record(StepRecord& r) const {
  const auto& integrator = *parts_.integrator;
  r.channels = static_cast<std::uint8_t>(channels_);
  r.dofs = static_cast<std::uint8_t>(parts_.recorded_dofs.size());
  for (int c = 0; c < channels_; ++c) {
    r.target_m[c] = targets_[c];
    r.command_m[c] = command_.displacement_m[c];
    r.measured_m[c] = feedback_.displacement_m[c];
    r.measured_force_n[c] = feedback_.force_n[c];
    r.specimen_restoring_force_n[c] = specimen_forces_[c];
    r.tracking_indicator_m2[c] = tracking_[c].value_m2();
    r.round_trip_s[c] = static_cast<double>(feedback_.round_trip_ns[c]) * 1e-9;
  }
  for (std::size_t i = 0; i < parts_.recorded_dofs.size(); ++i) {
    const Eigen::Index dof = parts_.recorded_dofs[i];
    r.displacement_m[i] = integrator.displacement()[dof];
    r.velocity_m_per_s[i] = integrator.velocity()[dof];
    r.acceleration_m_per_s2[i] = integrator.acceleration()[dof];
    r.restoring_force_n[i] = integrator.restoring_force()[dof];
  }
  r.input_energy_j = input_energy_j_;
  r.damping_energy_j = damping_energy_j_;
  r.restoring_energy_j = restoring_energy_j_;
  r.kinetic_energy_j = kinetic_energy_j_;
}

}  // namespace rpsd::coordinator
