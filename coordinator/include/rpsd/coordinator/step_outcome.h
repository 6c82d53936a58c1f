// How a step of a test ended, and which limit stopped it: shared by the loop that integrates
// the structure (rpsd_loop.h) and the exchange with the experimental sites it runs
// (experimental_exchange.h), which an outside integrator (OpenSees) may drive too.
#pragma once

#include <array>
#include <cstdint>

namespace rpsd::coordinator {

// What stopped the test, on which channel, at what value: one of the coordinator's limits
// (StepOutcome::kLimit) or a run-away (StepOutcome::kRunAway).
struct LimitStop {
  enum class Kind : std::uint8_t {
    kNone,
    kStroke,
    kIncrement,
    kForce,
    kTrackingError,    // |target - measured| beyond max_tracking_error_m
    kNodeLimit,        // a node's limit acted; value: its limit flags
    kEndStop,          // a piston reached the end of its stroke
    kValveSaturation,  // a servovalve stayed fully open; value: exchanges in a row
    kGeometry,         // a setup's geometry failed (StepOutcome::kGeometry); value: its SetupStatus
  };
  Kind kind = Kind::kNone;
  int channel = -1;
  double value = 0.0, bound = 0.0;
  // On a channel an experimental setup drives: which of its actuators (the limit acted on the
  // actuator's stroke or force) or which of its DOFs (on the DOF's target, force or tracking),
  // named for people ("site 1 actuator west", "site 1 DOF 2 rotation"), with the units of the
  // value. Filled in place on the real-time path: no allocation. Empty name: a plain channel.
  int setup = -1, actuator = -1, dof = -1;
  int held = -1;  // a channel in force control (held_force.h), by its index among them
  std::array<char, 64> name{};
  const char* unit = "m";  // of value and bound: m, rad, N or N·m (a string literal)
};
const char* limit_stop_name(LimitStop::Kind kind);

enum class StepOutcome : std::uint8_t {
  kOk,
  kRecordEnded,
  kLinkFailure,
  kIntegratorError,
  kNodeFault,
  kNonFinite,
  kLimit,    // a coordinator limit (limit_stop() says which)
  kRunAway,  // the test left the rig's envelope or diverged (limit_stop() says how)
  // An experimental setup's geometry failed: its Jacobian singular at the measured strokes,
  // or its Newton solve not converged; nothing more is sent (limit_stop() names the setup).
  kGeometry,
  // Set by the test around the loop, never by the loop itself:
  kResultsNotWritten,  // a write of the step records failed (a full disk)
  kInterrupted,        // the user asked the run to stop (SIGINT, SIGTERM)
  kRefused,            // a site's node serves another run, or runs at another rate (the link says which)
  kOperatorStop,       // an operator's stop (operator_commands/): ended in order after the step under way
  kOperatorAbort,      // an operator's abort: the coordinator stopped commanding, every node holds at once
  // A host program's compensator or structure (kind external) threw: its non-finite command
  // or force stopped the step before anything was sent or integrated, or the run after it.
  kHostCallFailed,
};
// The outcome's name for scripts (summary.json's stopped_by.kind): "node_fault", "limit", ...
const char* step_outcome_name(StepOutcome outcome);

}  // namespace rpsd::coordinator
