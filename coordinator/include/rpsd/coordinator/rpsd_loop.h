// One step of a real-time pseudodynamic test, the heart of rpsd:
//   integrator.begin_step(F(t+dt))                  F = -M iota a_g, or zero in free vibration
//   per iteration (1 for explicit schemes):
//     d = integrator.target_displacement(); target = partition.extract_commands(d)  (model -> specimen scale)
//     u[ch] = compensator[ch].command(target[ch]); link.send(u); link.receive(feedback)  (in-process or DDS alike)
//     compensator[ch].observe(target[ch], x_measured[ch])
//     integrator.set_measured_restoring_force(R_num(d) + scatter(R_exp))  R_exp: measured force, or k x_measured
//   integrator.end_step(); numerical.commit(); energy balance; record
// Under LoopTiming::kTargetNowForceDelayed (the RTHS benchmark's) the command is the previous
// step's target and R_exp the previous exchange's force (loop_timing.h).
// The parts are configured by the caller and only borrowed. step() is real-time safe: no allocation, no locks,
// no exceptions; problems come back as StepOutcome.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/coordinator/experimental_exchange.h"
#include "rpsd/coordinator/loop_timing.h"
#include "rpsd/coordinator/recorder.h"
#include "rpsd/coordinator/restoring_force.h"
#include "rpsd/integrators/integrator.h"
#include "rpsd/substructure/ground_motion_load.h"
#include "rpsd/substructure/numerical_model.h"
#include "rpsd/substructure/partition.h"
#include "rpsd/transport/link.h"

namespace rpsd::coordinator {

struct LoopParts {
  integrators::Integrator* integrator = nullptr;      // configured with M, C, K0 and dt
  substructure::NumericalModel* numerical = nullptr;  // M, C and R_num(d)
  const substructure::Partition* partition = nullptr;
  transport::Link* link = nullptr;
  std::vector<compensation::CommandCompensator*> compensators;  // one per channel, configured
  std::vector<RestoringForcePath> force_paths;                  // one per channel
  std::vector<Eigen::Index> recorded_dofs;                      // at most kMaxRecordedDofs
  std::span<const double> ground_acceleration_m_per_s2;         // at t = n dt (borrowed); empty: free vibration
  const substructure::GroundMotionLoad* ground_load = nullptr;  // F = -M iota a_g; needed with a record
  std::uint32_t test_id = 1;
  // This run's identity, on every command (0: the loop draws one): a node serves one run at a time.
  std::uint64_t run_id = 0;
  // As fast as possible, a full recorder queue makes the loop wait (nothing is lost); in
  // real time it drops and counts the record instead, so the loop never blocks.
  bool wait_for_recorder = true;
  // Lock-step (0): every step needs the feedback of its own command. Real time (> 0): a
  // feedback that misses its deadline is replaced by the newest measurement, counted and
  // flagged, as long as that measurement answers a command at most this many control
  // periods old; an older one (a silent node) stops the test.
  int max_feedback_age_periods = 0;
  // The coordinator's limits per channel (empty: none). A command beyond its stroke or
  // increment is never sent; a measured force or tracking error beyond its bound stops the
  // test at once.
  std::vector<CoordinatorLimits> limits;
  // A run-away also stops the test: a node's stroke or force limit acting, a piston on its
  // end stop, a servovalve fully open for longer than this many exchanges in a row.
  bool stop_on_node_limits = false;
  int max_valve_saturation_exchanges = 0;  // 0: not checked
  // Which target a step commands and which force it feeds back (loop_timing.h); the
  // benchmark's timing needs an integrator with one exchange per step.
  LoopTiming timing = LoopTiming::kEndOfStep;
  // The experimental setups: their channels' targets and restoring forces are their DOFs',
  // their commands and feedback their actuators' (setup_group.h).
  std::vector<SetupGroup> setups;
  // The channels in force control, after the structure's on the link (held_force.h).
  std::vector<HeldForceChannel> held_forces;
};

class RpsdLoop {
 public:
  // Checks the parts fit together and sizes every buffer. Throws std::invalid_argument
  // naming the mismatch. Not real-time safe.
  explicit RpsdLoop(LoopParts parts);

  // Starts at rest at displacement d0 (model scale) with the specimens' forces at d0
  // (specimen scale, one per channel). Resets compensators and indicators. Not real-time safe.
  void start(const Eigen::VectorXd& d0, std::span<const double> specimen_force0_n);

  // Advances the test by one integration step and records it. Real-time safe.
  StepOutcome step(Recorder& recorder);

  // The record of the last step taken (what step() handed to the recorder), unpacked from its
  // row when first asked for: a step writes only the row (most steps' records are never asked
  // for here). Real-time safe; the loop's thread only, while the recorder of that step lives.
  const StepRecord& last_record() const {
    if (last_row_) {
      last_layout_->unpack(last_row_, record_);
      last_row_ = nullptr;
    }
    return record_;
  }

  // Whether a full recorder queue makes step() wait (LoopParts::wait_for_recorder).
  void set_wait_for_recorder(bool wait) { parts_.wait_for_recorder = wait; }
  // Real time: how late the current cycle woke (recorded with the step). Real-time safe.
  void set_cycle_lateness_ns(std::int64_t ns) { cycle_lateness_ns_ = ns; }
  std::int64_t late_feedback_total() const { return exchange_.late_feedback_total(); }
  // Control periods between the newest feedback and the last command sent, as of the last
  // exchange (0: on time).
  std::int64_t feedback_age_periods() const { return exchange_.feedback_age_periods(); }
  // The coordinator limit that stopped the loop (kind kNone if none did).
  const LimitStop& limit_stop() const { return exchange_.limit_stop(); }

  // One exchange outside the integration (an operator's stop returning the actuators to
  // their start positions): the channels toward `targets` at test time `time_s` through the
  // same compensators, coordinator limits and setups, unrecorded. Real-time safe.
  StepOutcome exchange_only(const Eigen::VectorXd& targets, double time_s) {
    return exchange_.exchange(targets, time_s);
  }
  // ExperimentalExchange::set_compensated, for such exchanges. Real-time safe.
  void set_compensated(bool compensated) { exchange_.set_compensated(compensated); }

  std::int64_t step_index() const { return step_; }
  std::uint64_t run_id() const { return exchange_.run_id(); }
  const ExperimentalExchange& exchange() const { return exchange_; }
  // Ground-motion steps, or unlimited (-1).
  std::int64_t steps_available() const {
    const auto n = static_cast<std::int64_t>(parts_.ground_acceleration_m_per_s2.size());
    return n == 0 ? -1 : n - 1;
  }
  double dt_s() const { return parts_.integrator->dt_s(); }

 private:
  // The energy balance of the step just taken, over Dofs DOFs: 1 (the paper's SDOF, in
  // scalars) or Eigen::Dynamic (any count); one copy of the formulas for both, the size
  // chosen at construction (one_dof_).
  template <int Dofs>
  void energy_balance();
  // Hands this step's row to the recorder (in its queue, or in spare_row_ when a real-time
  // step drops it) and remembers where it is for last_record().
  void hand_off(Recorder& recorder);

  LoopParts parts_;
  ExperimentalExchange exchange_;
  int channels_ = 0;
  Eigen::Index dofs_ = 0;
  bool one_dof_ = false;
  // The numerical model's M and C for the energy balance, asked for once (one object each
  // for the model's life), not through a virtual call every step.
  const linalg::StructuralMatrix* mass_ = nullptr;
  const linalg::StructuralMatrix* damping_ = nullptr;
  Eigen::VectorXd force_, targets_, restoring_;
  // kTargetNowForceDelayed: the target of the step before, and the force of the exchange before.
  Eigen::VectorXd held_targets_, held_forces_;
  Eigen::VectorXd previous_d_, previous_v_, previous_r_, previous_f_, work_a_, work_b_, force_sum_, restoring_sum_;
  double ground_m_per_s2_ = 0.0;  // this step's ground acceleration, for its row
  // The last step's record, unpacked from its row (last_row_, laid out as last_layout_ says)
  // when asked for.
  mutable StepRecord record_;
  mutable const std::byte* last_row_ = nullptr;
  const RecordLayout* last_layout_ = nullptr;
  alignas(8) std::array<std::byte, RecordLayout::kMaxRowBytes> spare_row_{};  // a dropped step's row
  std::int64_t step_ = 0;
  std::int64_t cycle_lateness_ns_ = 0;
  std::int64_t oldest_age_this_step_ = 0;
  double input_energy_j_ = 0.0, damping_energy_j_ = 0.0, restoring_energy_j_ = 0.0, kinetic_energy_j_ = 0.0;
};

}  // namespace rpsd::coordinator
