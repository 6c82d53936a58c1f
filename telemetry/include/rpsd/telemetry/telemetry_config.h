// Whether a test publishes its telemetry, and at what sample rate (`output.telemetry`,
// `output.telemetry_samples_per_s` in a scenario; `rpsd run --telemetry`). Off by default:
// nothing a run writes changes either way (docs/telemetry.md).
#pragma once

namespace rpsd::telemetry {

struct TelemetryConfig {
  bool enabled = false;
  double max_samples_per_s = 256.0;  // of test time, per run
};

}  // namespace rpsd::telemetry
