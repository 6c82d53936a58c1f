// rpsd: one binary, one subcommand per job. Errors from any subcommand end here with a
// message naming what failed and a non-zero exit code.
#include <CLI/CLI.hpp>

#include "cli/commands.h"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"rpsd - real-time pseudodynamic (hybrid) testing"};
  app.require_subcommand(1);
  auto* analyze = app.add_subcommand("analyze", "Linear analysis of a servo system or an integrator");
  analyze->require_subcommand(0, 1);
  rpsd::cli::add_analyze_servo(*analyze);
  rpsd::cli::add_analyze_integrator_command(*analyze);
  rpsd::cli::add_run(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
