// Each rpsd subcommand registers itself on the CLI11 app from its own file.
#pragma once

#include <CLI/CLI.hpp>

namespace rpsd::cli {

/// `rpsd analyze SERVO.yaml [--json]`: linear analysis of a servo-system parameter file.
void add_analyze_servo(CLI::App& analyze);

/// `rpsd analyze integrator NAME ...`: amplification-matrix properties of a scheme.
void add_analyze_integrator_command(CLI::App& analyze);

/// `rpsd run SCENARIO --out DIR`: run a scenario, write results.
void add_run(CLI::App& app);

}  // namespace rpsd::cli
