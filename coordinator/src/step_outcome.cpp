#include "rpsd/coordinator/step_outcome.h"

namespace rpsd::coordinator {

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
    case LimitStop::Kind::kGeometry:
      return "geometry";
  }
  return "unknown";
}

const char* step_outcome_name(StepOutcome outcome) {
  switch (outcome) {
    case StepOutcome::kOk:
      return "ok";
    case StepOutcome::kRecordEnded:
      return "record_ended";
    case StepOutcome::kLinkFailure:
      return "link_failure";
    case StepOutcome::kIntegratorError:
      return "integrator_error";
    case StepOutcome::kNodeFault:
      return "node_fault";
    case StepOutcome::kNonFinite:
      return "non_finite";
    case StepOutcome::kLimit:
      return "limit";
    case StepOutcome::kRunAway:
      return "run_away";
    case StepOutcome::kGeometry:
      return "geometry";
    case StepOutcome::kResultsNotWritten:
      return "results_not_written";
    case StepOutcome::kInterrupted:
      return "interrupted";
    case StepOutcome::kRefused:
      return "refused";
    case StepOutcome::kOperatorStop:
      return "operator_stop";
    case StepOutcome::kOperatorAbort:
      return "operator_abort";
    case StepOutcome::kHostCallFailed:
      return "host_call_failed";
  }
  return "unknown";
}

}  // namespace rpsd::coordinator
