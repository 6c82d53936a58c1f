// One exchange with the experimental sites: the targets of every channel go through its
// compensator and the coordinator's limits, out over the link, and the measurement comes back
// checked (node faults, non-finite values, run-aways, the force limit) and turned into the
// specimens' restoring forces. On the channels an experimental setup drives, the targets are
// the DOFs' and go through the setup's geometry to the actuators' strokes, and the actuators'
// measured strokes and forces come back through it as the DOFs' displacements and forces
// (setup_group.h). The RPsD loop runs one per integrator iteration; `rpsd
// site-server` runs one per trial displacement OpenSees sends. Configured once, then
// exchange() is real-time safe: no allocation, no locks, no exceptions.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/compensator_call.h"
#include "rpsd/compensation/tracking_indicator.h"
#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/coordinator/held_force.h"
#include "rpsd/coordinator/record_layout.h"
#include "rpsd/coordinator/restoring_force.h"
#include "rpsd/coordinator/setup_group.h"
#include "rpsd/coordinator/step_outcome.h"
#include "rpsd/coordinator/step_record.h"
#include "rpsd/transport/link.h"

namespace rpsd::coordinator {

struct ExchangeParts {
  transport::Link* link = nullptr;
  std::vector<compensation::CommandCompensator*> compensators;  // one per channel, configured
  std::vector<RestoringForcePath> force_paths;                  // one per channel
  std::uint32_t test_id = 1;
  std::uint64_t run_id = 0;  // 0: drawn here
  // Lock-step (0): every exchange needs the feedback of its own command. Real time (> 0): a
  // feedback at most this many control periods old stands in for a late one (counted).
  int max_feedback_age_periods = 0;
  std::vector<CoordinatorLimits> limits;  // per channel, or empty: none
  bool stop_on_node_limits = false;
  int max_valve_saturation_exchanges = 0;  // 0: not checked
  // The experimental setups and the channels each drives (the other channels: one actuator
  // per DOF, as without any).
  std::vector<SetupGroup> setups;
  // The channels in force control (held_force.h), on the link channels after the structure's.
  std::vector<HeldForceChannel> held_forces;
};

class ExperimentalExchange {
 public:
  // Checks the parts fit together (std::invalid_argument naming the mismatch). Not real-time safe.
  explicit ExperimentalExchange(ExchangeParts parts);

  int channels() const { return channels_; }  // the structure's; the held forces' come after
  int held_forces() const { return static_cast<int>(parts_.held_forces.size()); }
  std::uint64_t run_id() const { return command_.run_id; }

  // At rest: the actuators hold `targets` (specimen scale), the specimens carry `forces`.
  // Resets compensators and indicators. Not real-time safe.
  void start(const Eigen::VectorXd& targets, std::span<const double> specimen_force_n);

  // Commands the channels toward `targets` (specimen scale, one per channel) at test time `time_s` and takes
  // the measurement. kOk: specimen_forces() holds this exchange's restoring forces. Otherwise
  // nothing more may be sent; limit_stop() says which limit when one acted. Real-time safe.
  StepOutcome exchange(const Eigen::VectorXd& targets, double time_s);

  const Eigen::VectorXd& specimen_forces() const { return specimen_forces_; }
  // The targets of the last exchange (specimen scale; a setup's channels: its DOFs').
  const Eigen::VectorXd& targets() const { return targets_; }
  // Channel c's last command where its target lives: a plain channel's command, a setup DOF's
  // compensated command (compensated on the DOFs) or its target (compensated on the
  // actuators). Where an uncompensated ramp starts without a jump. Real-time safe.
  double command_in_target_space(int c) const;
  // Off: every command is its target, no compensator acts (an operator's return to the start
  // positions: a slow ramp has no lag worth compensating, and a compensator's lead on the
  // ramp's first exchange would jump). Real-time safe.
  void set_compensated(bool compensated) { compensated_ = compensated; }
  const transport::CommandSample& command() const { return command_; }
  const transport::FeedbackSample& feedback() const { return feedback_; }
  const LimitStop& limit_stop() const { return limit_stop_; }
  std::int64_t exchanges() const { return exchange_; }
  // Real time: exchanges answered by an older measurement, and the age of the last one's.
  std::int64_t late_feedback_total() const { return late_total_; }
  std::int64_t feedback_age_periods() const { return feedback_age_; }

  // The setups, as configured (their geometry checked). Not real-time safe.
  int setup_count() const { return static_cast<int>(groups_.size()); }
  const setups::PlanarSetup& setup(int g) const { return groups_[static_cast<std::size_t>(g)].setup; }

  // The channels' part of a step record (targets, commands, measurements, forces, tracking,
  // round trips). Real-time safe.
  void fill_channels(StepRecord& r) const;
  // The same into a row of the recorder's queue, in place (the loop's step: no StepRecord
  // between). Real-time safe.
  void fill_channels(RecordLayout::Row row) const;
  // Channel c's command-to-feedback time of the last exchange, s (its record's round_trip_s).
  // Real-time safe.
  double round_trip_s(int c) const {
    return static_cast<double>(feedback_.round_trip_ns[static_cast<std::size_t>(c)]) * 1e-9;
  }

 private:
  template <typename Out>
  void write_channels(Out out) const;  // both fill_channels: into a record or a row
  // One setup's state: the DOF and actuator vectors of the exchange under way (fixed size).
  struct Group {
    Group(SetupGroup p, setups::PlanarSetup s) : parts(std::move(p)), setup(std::move(s)) {}
    SetupGroup parts;
    setups::PlanarSetup setup;
    setups::SetupVector dof_target, dof_command, stroke_target, stroke_command, stroke_measured, dof_measured,
        actuator_force, dof_force, offset, last_dof_command;
    std::vector<std::array<char, 64>> actuator_names, dof_names;
    std::array<char, 64> name{};  // "site 1 setup"
    std::vector<const char*> dof_units, dof_force_units;
  };

  // The exchange of N channels, N = 1 or kAnyChannels (experimental_exchange.cpp says when).
  static constexpr int kAnyChannels = -1;
  template <int N>
  StepOutcome exchange_of(const Eigen::VectorXd& targets, double time_s);
  template <int N>
  int channel_count() const;
  template <int N>
  bool in_setup(int c) const;
  template <int N>
  std::span<Group> setup_groups();
  template <int N>
  bool holds_forces() const;

  template <int N>
  bool commands_within_limits();                 // fills limit_stop_ when not
  bool held_and_setup_commands_within_limits();  // the part of the above for held forces and setups
  // The held forces' commands at test time `time_s`: each ramps from its force at rest.
  void command_held_forces(double time_s);
  // The held forces' measurements against their limits: kOk, or kLimit / kRunAway with
  // limit_stop_ filled.
  StepOutcome check_held_forces();
  void stop_on_held(int k, LimitStop::Kind kind, double value, double bound, const char* unit);
  template <int N>
  StepOutcome run_away();        // kOk, or kRunAway with limit_stop_ filled
  StepOutcome setup_run_away();  // the part of the above for setups' actuators
  // A setup's channels: the DOF targets through the geometry to the actuators' commands.
  void command_setup(Group& g);
  // A setup's channels: the measured strokes and forces back to the DOFs'; kGeometry, kLimit
  // or kRunAway with limit_stop_ filled when the geometry or a DOF's limit stops the test.
  StepOutcome feedback_setup(Group& g);
  void stop_on_actuator(const Group& g, int i, LimitStop::Kind kind, double value, double bound);
  void stop_on_dof(const Group& g, int i, LimitStop::Kind kind, double value, double bound, bool force);

  ExchangeParts parts_;
  int channels_ = 0;
  Eigen::VectorXd targets_, specimen_forces_;
  std::vector<compensation::TrackingIndicator> tracking_;
  transport::CommandSample command_;
  transport::FeedbackSample feedback_;
  std::int64_t exchange_ = 0;
  std::int64_t late_total_ = 0;
  std::int64_t feedback_age_ = 0;
  LimitStop limit_stop_;
  std::array<double, transport::kMaxChannels> last_sent_m_{};
  int saturated_exchanges_ = 0;
  bool compensated_ = true;
  std::vector<Group> groups_;
  int link_channels_ = 0;  // the structure's channels and the held forces'
  // Per channel: its setup and its index there (-1: no setup drives it).
  std::array<int, transport::kMaxChannels> group_of_{}, index_in_group_{};
  // Per channel: its compensator as a step calls it (parts_.compensators, a phase lead directly).
  std::array<compensation::CompensatorCall, transport::kMaxChannels> compensator_calls_{};
  bool one_plain_channel_ = false;  // one channel, no setups, no held forces: exchange_of<1>
};

}  // namespace rpsd::coordinator
