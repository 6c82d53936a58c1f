// The body of `rpsd servo-node` and `rpsd controller-emulator`: build the actuator and the
// controller from the setup, serve until stopped, and say what happened (the --summary
// JSON). The command line only reads the file, handles signals and writes the summary.
// Not real-time safe to call; the loops inside are.
#pragma once

#include <atomic>
#include <iosfwd>
#include <nlohmann/json.hpp>

#include "rpsd/node/servo_node_setup.h"

namespace rpsd::node {

struct ServeOptions {
  double duration_s = 0.0;  // stop after this long (0: only when `stop` is set)
};

// Serves the setup's site over DDS until `stop` or the duration; progress lines go to `log`.
// Returns the summary (counters, limit events, timing). An actuator that cannot start (its
// controller does not answer, refuses, or measures elsewhere) returns at once a summary with
// `started: false` and `start_failure`, nothing moved. Throws what building the actuator, the
// controller or the DDS endpoint throws.
nlohmann::json serve_site(const ServoNodeSetup& setup, const ServeOptions& options, const std::atomic<bool>& stop,
                          std::ostream& log);

// Stands in for a hardware controller on UDP until `stop` or the duration.
nlohmann::json emulate_controller(const ControllerEmulatorSetup& setup, const ServeOptions& options,
                                  const std::atomic<bool>& stop, std::ostream& log);

}  // namespace rpsd::node
