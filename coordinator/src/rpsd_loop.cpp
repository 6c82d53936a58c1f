#include "rpsd/coordinator/rpsd_loop.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {

namespace {

ExchangeParts exchange_parts(const LoopParts& p) {
  if (!p.integrator || !p.numerical || !p.partition || !p.link) {
    throw std::invalid_argument("RpsdLoop: integrator, numerical model, partition and link are all required");
  }
  if (static_cast<int>(p.compensators.size()) != static_cast<int>(p.partition->channels())) {
    throw std::invalid_argument("RpsdLoop: one compensator and one restoring-force path per actuator channel");
  }
  return {p.link,
          p.compensators,
          p.force_paths,
          p.test_id,
          p.run_id,
          p.max_feedback_age_periods,
          p.limits,
          p.stop_on_node_limits,
          p.max_valve_saturation_exchanges,
          p.setups,
          p.held_forces};
}

}  // namespace

RpsdLoop::RpsdLoop(LoopParts parts) : parts_(std::move(parts)), exchange_(exchange_parts(parts_)) {
  dofs_ = parts_.numerical->dofs();
  one_dof_ = dofs_ == 1;
  mass_ = &parts_.numerical->mass();
  damping_ = &parts_.numerical->damping();
  channels_ = exchange_.channels();
  if (parts_.integrator->size() != dofs_ || parts_.partition->dofs() != dofs_) {
    throw std::invalid_argument("RpsdLoop: the integrator, numerical model and partition have different DOF counts");
  }
  if (static_cast<int>(parts_.recorded_dofs.size()) > kMaxRecordedDofs) {
    throw std::invalid_argument("RpsdLoop: at most " + std::to_string(kMaxRecordedDofs) + " recorded DOFs");
  }
  for (Eigen::Index dof : parts_.recorded_dofs) {
    if (dof < 0 || dof >= dofs_)
      throw std::invalid_argument("RpsdLoop: recorded DOF " + std::to_string(dof) + " out of range");
  }
  if (!parts_.ground_acceleration_m_per_s2.empty() && parts_.ground_load == nullptr) {
    throw std::invalid_argument("RpsdLoop: a ground-motion record needs the ground-motion load (M iota)");
  }
  for (auto* v : {&force_, &restoring_, &previous_d_, &previous_v_, &previous_r_, &previous_f_, &work_a_, &work_b_,
                  &force_sum_, &restoring_sum_}) {
    *v = Eigen::VectorXd::Zero(dofs_);
  }
  targets_ = held_targets_ = held_forces_ = Eigen::VectorXd::Zero(channels_);
  if (parts_.timing == LoopTiming::kTargetNowForceDelayed && parts_.integrator->iterations_per_step() != 1) {
    throw std::invalid_argument(
        "RpsdLoop: loop timing target_now_force_delayed needs one exchange per step; the integrator takes " +
        std::to_string(parts_.integrator->iterations_per_step()));
  }
}

void RpsdLoop::start(const Eigen::VectorXd& d0, std::span<const double> specimen_force0_n) {
  if (d0.size() != dofs_ || static_cast<int>(specimen_force0_n.size()) != channels_) {
    throw std::invalid_argument("RpsdLoop::start: d0 needs one value per DOF and one force per channel");
  }
  parts_.partition->extract_commands(d0, targets_);
  exchange_.start(targets_, specimen_force0_n);
  held_targets_ = targets_;
  held_forces_ = exchange_.specimen_forces();
  parts_.numerical->restoring_force(d0, restoring_);
  parts_.partition->add_forces(exchange_.specimen_forces(), restoring_);
  parts_.numerical->commit();
  force_.setZero();
  if (parts_.ground_load && !parts_.ground_acceleration_m_per_s2.empty()) {
    parts_.ground_load->force(parts_.ground_acceleration_m_per_s2[0], force_);
  }
  parts_.integrator->initialize(d0, Eigen::VectorXd::Zero(dofs_), restoring_, force_);
  step_ = 0;
  record_ = StepRecord{};
  last_row_ = nullptr;
  previous_d_ = d0;
  previous_v_.setZero();
  previous_r_ = restoring_;
  previous_f_ = force_;
  input_energy_j_ = damping_energy_j_ = restoring_energy_j_ = kinetic_energy_j_ = 0.0;
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
    // The benchmark's timing (loop_timing.h): send the step before's target and feed the
    // exchange before's force, then hold this step's for the next.
    const bool benchmark_timing = parts_.timing == LoopTiming::kTargetNowForceDelayed;
    const double time_s = static_cast<double>(exchange_.exchanges() + 1) * integrator.dt_s() / iterations;
    const Eigen::VectorXd& command_targets = benchmark_timing ? held_targets_ : targets_;
    if (const StepOutcome outcome = exchange_.exchange(command_targets, time_s); outcome != StepOutcome::kOk) {
      return outcome;
    }
    oldest_age_this_step_ = std::max(oldest_age_this_step_, exchange_.feedback_age_periods());
    numerical.restoring_force(d, restoring_);
    partition.add_forces(benchmark_timing ? held_forces_ : exchange_.specimen_forces(), restoring_);
    if (benchmark_timing) {
      held_targets_ = targets_;
      held_forces_ = exchange_.specimen_forces();
    }
    if (integrator.set_measured_restoring_force(restoring_) != integrators::StepStatus::kOk) {
      return StepOutcome::kIntegratorError;
    }
  }
  if (integrator.end_step() != integrators::StepStatus::kOk) return StepOutcome::kIntegratorError;
  numerical.commit();
  ++step_;

  if (one_dof_) {
    energy_balance<1>();
  } else {
    energy_balance<Eigen::Dynamic>();
  }
  ground_m_per_s2_ = ground;
  hand_off(recorder);
  return StepOutcome::kOk;
}

namespace {

// A model vector as the energy balance reads it: of fixed size for one DOF (a scalar to the
// compiler), the VectorXd itself otherwise. Eigen's dot of size 1 is a0 b0 either way, and at
// any other size the expressions are today's, so the energies keep every digit.
template <int Dofs>
decltype(auto) sized(const Eigen::VectorXd& v) {
  if constexpr (Dofs == Eigen::Dynamic) {
    return (v);
  } else {
    return Eigen::Map<const Eigen::Matrix<double, Dofs, 1>>(v.data());
  }
}

}  // namespace

template <int Dofs>
void RpsdLoop::energy_balance() {
  // By the trapezoidal rule over the step (model scale): input = sum F.dd, damping = sum
  // (Cv).dd, restoring = sum R.dd, kinetic = 1/2 v'Mv. The sums and differences in one pass
  // that also keeps this step's state for the next (each entry as Eigen's expressions
  // computed it); the dot products stay Eigen's, whose order of summation the recorded
  // energies' digits depend on.
  const auto& integrator = *parts_.integrator;
  const Eigen::VectorXd& v = integrator.velocity();
  const Eigen::Index n = Dofs == Eigen::Dynamic ? dofs_ : Dofs;
  {
    const double *d = integrator.displacement().data(), *vv = v.data(), *r = integrator.restoring_force().data(),
                 *f = force_.data();
    double *pd = previous_d_.data(), *pv = previous_v_.data(), *pr = previous_r_.data(), *pf = previous_f_.data();
    double *dd = work_a_.data(), *v_sum = work_b_.data(), *f_sum = force_sum_.data(), *r_sum = restoring_sum_.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      dd[i] = d[i] - pd[i];
      f_sum[i] = pf[i] + f[i];
      r_sum[i] = pr[i] + r[i];
      v_sum[i] = vv[i] + pv[i];
      pd[i] = d[i];
      pv[i] = vv[i];
      pr[i] = r[i];
      pf[i] = f[i];
    }
  }
  input_energy_j_ += 0.5 * sized<Dofs>(force_sum_).dot(sized<Dofs>(work_a_));
  restoring_energy_j_ += 0.5 * sized<Dofs>(restoring_sum_).dot(sized<Dofs>(work_a_));
  damping_->multiply(work_b_, restoring_);  // restoring_ reused as scratch: C (v + v_prev)
  damping_energy_j_ += 0.5 * sized<Dofs>(restoring_).dot(sized<Dofs>(work_a_));
  mass_->multiply(v, work_b_);
  kinetic_energy_j_ = 0.5 * sized<Dofs>(v).dot(sized<Dofs>(work_b_));
}

void RpsdLoop::hand_off(Recorder& recorder) {
  const RecordLayout& layout = recorder.layout();
  const std::byte* written = nullptr;
  // The step's row, in place: the loop's part here, the channels' from the exchange.
  const auto write = [&](std::byte* at) {
    const RecordLayout::Row row(layout, at);
    const auto& integrator = *parts_.integrator;
    const Eigen::Index* const recorded = parts_.recorded_dofs.data();
    const auto count = static_cast<int>(parts_.recorded_dofs.size());
    row.header(step_, integrator.time_s(), ground_m_per_s2_, static_cast<std::uint8_t>(count),
               static_cast<std::uint8_t>(std::min<std::int64_t>(oldest_age_this_step_, 255)), input_energy_j_,
               kinetic_energy_j_, damping_energy_j_, restoring_energy_j_,
               static_cast<double>(cycle_lateness_ns_) * 1e-9);
    exchange_.fill_channels(row);
    const double *d = integrator.displacement().data(), *v = integrator.velocity().data(),
                 *a = integrator.acceleration().data(), *r = integrator.restoring_force().data();
    for (int i = 0; i < count; ++i) {
      const Eigen::Index dof = recorded[i];
      row.dof(i, d[dof], v[dof], a[dof], r[dof]);
    }
    written = at;
  };
  if (parts_.wait_for_recorder) {
    recorder.record_or_wait_in_place(write);
  } else if (!recorder.record_in_place(write)) {
    write(spare_row_.data());  // dropped (counted): last_record() still reads it
  }
  last_row_ = written;
  last_layout_ = &layout;
}

}  // namespace rpsd::coordinator
