// Reads a servo-system parameter file (see examples/servo/paper-mts-244.yaml for the schema).
#pragma once

#include <filesystem>

#include "rpsd/servo/servo_parameters.h"

namespace rpsd::scenarios {

// Throws ConfigError naming file, line, column and key path for any missing, unknown or
// out-of-range key. Not real-time safe.
servo::ServoSystemParameters load_servo_parameters(const std::filesystem::path& file);

}  // namespace rpsd::scenarios
