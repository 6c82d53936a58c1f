// Whether a test publishes its telemetry, and at what sample rate (`output.telemetry`,
// `output.telemetry_samples_per_s` in a scenario; `rpsd run --telemetry`). Off by default:
// nothing a run writes changes either way (docs/telemetry.md).
#pragma once

#include <limits>

#include "rpsd/telemetry/effective_damping_identifier.h"

namespace rpsd::telemetry {

struct TelemetryConfig {
  bool enabled = false;
  double max_samples_per_s = 256.0;  // of test time, per run
  // Not read from a file: the delay theory's damping ratio of the lowest mode, filled in before
  // the run (studies::predicted_lowest_mode_damping) for the monitors; NaN: not predicted.
  double predicted_effective_damping = std::numeric_limits<double>::quiet_NaN();
  // Not read from a file either: the lowest mode the identified damping is projected on
  // (studies::lowest_mode_for_identification); unknown: no identified damping.
  LowestMode lowest_mode;
};

}  // namespace rpsd::telemetry
