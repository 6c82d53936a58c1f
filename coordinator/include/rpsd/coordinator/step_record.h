// What the coordinator records at every step, fixed size so that it is built without
// allocation; the recorder's queue carries it packed to the test's size (record_layout.h).
#pragma once

#include <array>
#include <cstdint>

#include "rpsd/transport/messages.h"

namespace rpsd::coordinator {

inline constexpr int kMaxRecordedDofs = 8;

struct StepRecord {
  std::int64_t step = 0;
  double time_s = 0.0;
  double ground_acceleration_m_per_s2 = 0.0;
  std::uint8_t channels = 0;
  std::uint8_t dofs = 0;
  // Per actuator channel, specimen scale. On a channel an experimental setup drives, the
  // actuator's view: target, command and measurement are its strokes (m, the calibration
  // offset taken off), the force its load cell's.
  std::array<double, transport::kMaxChannels> target_m{};
  std::array<double, transport::kMaxChannels> command_m{};
  std::array<double, transport::kMaxChannels> measured_m{};
  std::array<double, transport::kMaxChannels> measured_force_n{};
  // The specimen's restoring force the test used (the measured force, or k x measured).
  std::array<double, transport::kMaxChannels> specimen_restoring_force_n{};
  std::array<double, transport::kMaxChannels> tracking_indicator_m2{};
  // The DOF view of the same channels (a setup's DOF i on its actuator i's channel): the DOF's
  // target, its displacement solved from the measured strokes and its force Jᵀ f (m or rad,
  // N or N·m by the DOF's motion). Without a setup: the channel's own target, measurement
  // and load-cell force.
  std::array<double, transport::kMaxChannels> dof_target_m{};
  std::array<double, transport::kMaxChannels> dof_measured_m{};
  std::array<double, transport::kMaxChannels> dof_force_n{};
  // Per channel in force control (held_force.h), in their order: the force commanded (the
  // ramp), the piston's measured stroke and its load cell's force.
  std::uint8_t held = 0;
  std::array<double, transport::kMaxChannels> held_force_command_n{};
  std::array<double, transport::kMaxChannels> held_measured_m{};
  std::array<double, transport::kMaxChannels> held_measured_force_n{};
  // Per recorded model DOF, model scale.
  std::array<double, kMaxRecordedDofs> displacement_m{};
  std::array<double, kMaxRecordedDofs> velocity_m_per_s{};
  std::array<double, kMaxRecordedDofs> acceleration_m_per_s2{};
  std::array<double, kMaxRecordedDofs> restoring_force_n{};
  // Energy balance, J (see energy_balance.h).
  double input_energy_j = 0.0;
  double kinetic_energy_j = 0.0;
  double damping_energy_j = 0.0;
  double restoring_energy_j = 0.0;
  std::uint32_t node_status = 0;
  std::uint32_t limit_flags = 0;
  // Timing (zero as fast as possible in process).
  // Command-to-feedback time of each channel's site this step, s.
  std::array<double, transport::kMaxChannels> round_trip_s{};
  double cycle_lateness_s = 0.0;          // how late the paced cycle woke after its deadline
  std::uint8_t feedback_age_periods = 0;  // periods the feedback used was behind its command (0: on time; real time)
};

}  // namespace rpsd::coordinator
