// rpsd: one binary, one subcommand per job. Errors from any subcommand end here with a
// message naming what failed and an exit code: 0 success, 1 failure, 2 bad input (scenario,
// parameter or record files), 3 test aborted (the reason is in its summary.json), 4 the dry
// run says the test is not ready.
#include <CLI/CLI.hpp>

#include "rpsd/commands.h"
#include "rpsd/realtime/large_blocks.h"
#include "rpsd/scenarios/config_error.h"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  // Before anything allocates, so that Cyclone's first receive buffer gets a mapping of its
  // own too: a run or a node of hours must not grow its heap (large_blocks.h).
  rpsd::realtime::map_large_blocks_separately();
  CLI::App app{"rpsd - real-time pseudodynamic (hybrid) testing"};
  app.require_subcommand(1);
  auto* analyze = app.add_subcommand("analyze", "Linear analysis of a servo system or an integrator");
  analyze->require_subcommand(0, 1);
  rpsd::cli::add_analyze_servo(*analyze);
  rpsd::cli::add_analyze_integrator_command(*analyze);
  rpsd::cli::add_run(app);
  rpsd::cli::add_validate(app);
  rpsd::cli::add_plot(app);
  rpsd::cli::add_servo_node(app);
  rpsd::cli::add_reference(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const rpsd::scenarios::ConfigError& e) {
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return 2;
  } catch (const rpsd::cli::TestAborted& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return 3;
  } catch (const rpsd::cli::DryRunNotReady& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
