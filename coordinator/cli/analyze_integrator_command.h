#pragma once
// `rpsd analyze integrator NAME [--rho-inf R | --alpha A] --omega-dt LIST --damping Z [--json]`:
// spectral radius, period ratio and numerical damping from the amplification matrix of
// a scheme, and its stability limit.
#include <CLI/CLI.hpp>

namespace rpsd::cli {

/// Registers the `integrator` subcommand under `analyze`.
void add_analyze_integrator_command(CLI::App& analyze);

}  // namespace rpsd::cli
