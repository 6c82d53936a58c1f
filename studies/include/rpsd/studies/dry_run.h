// The pre-test check (`rpsd run --dry-run`): the scenario against its simulated plant, in this
// process and as fast as possible, before any hardware moves. It predicts each channel's peak
// stroke, velocity, force, tracking error and servovalve opening against the coordinator's
// limits and the converters' rails, with the margin left to each (warned below 10 %), and the
// stability margin: the servo loop's proportional gain against its Routh bound, and for every
// structural mode the damping left and the delay margin, from delay theory per mode
// (s^2 + c s + k_n + g k_e e^{-s tau} = 0, mass-normalised) with the gain g and delay tau of
// the compensator and plant in series measured by a sine test at the mode's frequency.
// Given the servo nodes' own files (`--node FILE`), it also checks each channel's command
// against the limits its node enforces: the layer that stops the test on the rig.
// Not real-time safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rpsd/coordinator/rpsd_loop.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/node/servo_node_config.h"
#include "rpsd/studies/converter_rails.h"
#include "rpsd/studies/pretest_checks.h"

namespace rpsd::studies {

// The limits one servo node enforces on its site (from its file, as `rpsd servo-node` reads it).
struct NodeLimits {
  std::string name;  // the node file, for messages
  std::uint32_t test_id = 0, site_id = 0;
  double control_period_s = 1.0 / 1024.0;
  // The site's channels, in the test's channel order (how the coordinator addresses them):
  // its structure's, then its held forces'.
  std::vector<node::ChannelLimits> channels;
  // Each channel's control mode as its file declares it (empty: not known, not checked).
  std::vector<servo::ControlMode> control;
};

// One channel's peaks against its node's limits.
struct NodeCheck {
  std::string node;
  node::ChannelLimits limits;
  double control_period_s = 1.0 / 1024.0;      // the node's
  double peak_command_velocity_m_per_s = 0.0;  // |command change| / the node's control period
  bool within_limits = true;
};

struct ChannelPrediction {
  int channel = 0;
  std::uint32_t site_id = 1;
  double peak_command_m = 0.0, peak_displacement_m = 0.0, peak_velocity_m_per_s = 0.0, peak_increment_m = 0.0;
  double peak_force_n = 0.0;
  double peak_target_m = 0.0;                  // what the integrator asked for, before compensation
  double peak_tracking_error_m = 0.0;          // |measured - target|
  std::optional<NodeCheck> node;               // when the site's node file was given
  std::optional<double> peak_valve_opening;    // |x_v| of the servovalve, 0..1 (servo model only)
  std::optional<double> tracking_delay_ms;     // measured lags target by this (negative: leads)
  bool tracking_delay_at_window_edge = false;  // at +-200 ms: the true delay may lie beyond
  coordinator::CoordinatorLimits limits;
  double rig_velocity_m_per_s = servo::Envelope::kNone;  // the rig's envelope
  ConverterRails rails;
  // The margin left to every limit: the coordinator's, the rig's velocity, the node's (when
  // given) and the converters' rails.
  std::vector<LimitMargin> margins;
  bool within_limits = true;  // within the coordinator's limits (and the node's, when given)
  bool rail_contact = false;  // a converter reached its rail: the signal was clamped
};

// A DOF an experimental setup drives, from the same simulated run: its target, its
// displacement solved from the measured strokes and its force Jᵀ f, against the DOF's own
// limits (experimental[].limits as given: the rig's envelope is its actuators', which the
// channel's prediction above holds). Units by the DOF's motion: m and N, or rad and N·m.
struct DofPrediction {
  int channel = 0;
  std::uint32_t site_id = 1;
  std::string motion;  // translation_x, translation_y, rotation
  double peak_target_m = 0.0, peak_displacement_m = 0.0, peak_force_n = 0.0, peak_tracking_error_m = 0.0;
  coordinator::CoordinatorLimits limits;
  bool within_limits = true;
};

// An actuator that holds a force (held_forces[]), from the same simulated run: its ramp and
// limits as the test holds them, how well the force was held once ramped and how far its
// piston went.
struct HeldForcePrediction {
  std::string name;  // "site 1 held force axial"
  std::uint32_t site_id = 1;
  int channel = 0;  // its link channel, after the structure's
  double force_n = 0.0, max_force_rate_n_per_s = 0.0, force_at_rest_n = 0.0, ramp_s = 0.0;
  coordinator::HeldForceLimits limits;
  double max_force_error_after_ramp_n = 0.0;  // NaN: the run stopped before the ramp's end
  double peak_measured_m = 0.0;               // |measured stroke|
  bool within_limits = true;
};

struct ModePrediction {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;            // of the structure alone (no delay)
  double experimental_share = 0.0;       // k_e / k of the mode
  double loop_gain = 1.0;                // compensator and plant, measured/target at the mode's frequency
  double loop_delay_ms = 0.0;            // their equivalent delay there (negative: a lead)
  double predicted_damping_ratio = 0.0;  // with that gain and delay
  double critical_delay_ms = 0.0;        // +inf: stable for every delay
};

struct DryRunReport {
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
  coordinator::LimitStop limit_stop;
  std::int64_t steps = 0, steps_planned = 0;
  // Per channel: what its actuator sees (with a setup, the actuator's stroke and load cell
  // against the actuator's limits).
  std::vector<ChannelPrediction> channels;
  std::vector<DofPrediction> dofs;               // the DOFs setups drive (empty without setups)
  std::vector<HeldForcePrediction> held_forces;  // empty without held forces
  double residual_delay_ms = 0.0;                // the channels' mean tracking delay
  std::vector<ModePrediction> modes;
  // Servo model only: its proportional gain and the largest stable one (eigenvalues of the
  // full linear model with the specimen).
  std::optional<double> p_gain, max_stable_p_gain;
  std::optional<double> actuator_cutoff_hz;  // servo model only (linear analysis)
  // A margin below kMarginWarning, a command well above its target, a mode above the cut-off.
  std::vector<std::string> warnings;
  // Completed, every peak within its limit, no converter at its rail, every mode damped.
  bool within_limits = true;
};

// Runs the scenario's test (not the reference) with its simulated plant, whatever its transport
// and clock say. Throws what building the test throws, and std::invalid_argument naming the
// node file when a node serves another test, an unknown or repeated site, another number
// of channels than the scenario gives its site, or a channel in another control mode than the
// scenario's (a held force's channel in force control, every other in displacement control).
DryRunReport dry_run(const hybrid_test::TestConfig& scenario, const std::vector<NodeLimits>& nodes = {});

// The scenario's test with its simulated plant in this process, as fast as possible, publishing
// no telemetry: what a prediction before the run builds to learn the model.
hybrid_test::TestConfig simulated_in_process(const hybrid_test::TestConfig& scenario);

// The delay theory's damping ratio of the scenario's lowest mode with its compensated simulated
// plant (as the dry run's table gives it), without taking a step: for the telemetry's status.
// NaN when it cannot be predicted (OpenSees sites, a model the dry run refuses).
double predicted_lowest_mode_damping(const hybrid_test::TestConfig& scenario);

}  // namespace rpsd::studies
