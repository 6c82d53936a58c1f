// What a scenario says about operator commands (section `operator_commands`): whether a run
// with DDS Security off acts on them, and whether an operator's stop returns the actuators to
// their start positions, and how fast.
#pragma once

namespace rpsd::operator_commands {

struct OperatorCommandsConfig {
  // Security off: act on operator commands at all (anyone on the test's DDS network can then
  // send them). With DDS Security on, the permissions decide (the operator role).
  bool enabled = false;
  // Stop: after holding, ramp every channel's target back to where it started, through the
  // exchange (compensation, the coordinator's limits, a setup's geometry), at this velocity.
  bool return_to_start = false;
  double return_velocity_m_per_s = 0.0;  // required (> 0) with return_to_start
};

}  // namespace rpsd::operator_commands
