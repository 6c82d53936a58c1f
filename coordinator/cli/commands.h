// Each rpsd subcommand registers itself on the CLI11 app from its own file.
#pragma once

#include <CLI/CLI.hpp>

namespace rpsd::cli {

/// `rpsd analyze SERVO.yaml [--json]`: linear analysis of a servo-system parameter file.
void add_analyze_servo(CLI::App& analyze);

}  // namespace rpsd::cli
