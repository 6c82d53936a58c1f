// rpsd: one binary, one subcommand per job. Errors from any subcommand end here with a
// message naming what failed and one of the exit codes of exit_codes.h.
#include <CLI/CLI.hpp>
#include <csignal>
#include <exception>
#include <iostream>
#include <stdexcept>

#include "exit_codes.h"
#include "rpsd/build_info/build_info.h"
#include "rpsd/commands.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/output/results_files.h"
#include "rpsd/realtime/large_blocks.h"
#include "rpsd/scenarios/config_error.h"

int main(int argc, char** argv) {
  using namespace rpsd::cli;
  // Before anything allocates, so that Cyclone's first receive buffer gets a mapping of its
  // own too: a run or a node of hours must not grow its heap (large_blocks.h).
  rpsd::realtime::map_large_blocks_separately();
  // A file that may not grow further (ulimit -f) is a failed write to report, not a signal
  // that kills the run before it can say so.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"rpsd - real-time pseudodynamic (hybrid) testing"};
  app.set_version_flag(
      "--version", std::string("rpsd ") + rpsd::build_info::version() + " (commit " + rpsd::build_info::commit() + ")");
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 ok, 1 internal error, 2 bad input, 3 test stopped before its end, 4 not ready (dry run, or no "
      "servo node answered, or a node's actuator did not start), "
      "5 results not written, 6 interrupted (SIGINT/SIGTERM), 7 rpsd stop: refused, 8 rpsd stop: no answer");
  auto* analyze = app.add_subcommand("analyze", "Linear analysis of a servo system or an integrator");
  analyze->require_subcommand(0, 1);
  add_analyze_servo(*analyze);
  add_analyze_integrator_command(*analyze);
  add_run(app);
  add_validate(app);
  add_plot(app);
  add_servo_node(app);
  add_plugin_site_emulator(app);
  add_speedgoat_emulator(app);
  add_site_server(app);
  add_host_check(app);
  add_stop(app);
  add_monitor(app);
  add_reference(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    app.exit(e);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    // A missing or wrong option, a file that does not exist: bad input like a bad key.
    app.exit(e);
    return kExitBadInput;
  } catch (const rpsd::scenarios::ConfigError& e) {
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const rpsd::ground_motion::RecordError& e) {
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const TestStopped& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return kExitStopped;
  } catch (const DryRunNotReady& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return kExitNotReady;
  } catch (const NodeNotReady& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return kExitNotReady;
  } catch (const RunNotReady& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return kExitNotReady;
  } catch (const rpsd::output::ResultsNotWritten& e) {
    std::cerr << "rpsd: error: results not written: " << e.what() << '\n';
    return kExitResultsNotWritten;
  } catch (const RunInterrupted& e) {
    std::cerr << "rpsd: " << e.what() << '\n';
    return kExitInterrupted;
  } catch (const OperatorCommandRefused& e) {
    std::cerr << "rpsd stop: " << e.what() << '\n';
    return kExitCommandRefused;
  } catch (const NoOperatorReply& e) {
    std::cerr << "rpsd stop: " << e.what() << '\n';
    return kExitNoAnswer;
  } catch (const std::invalid_argument& e) {
    // Inputs that do not fit together (a node file for another test, an integrator option
    // it does not take, an --out folder in use: output::OutputFolderInUse).
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rpsd: error: " << e.what() << '\n';
    return kExitInternalError;
  }
  return kExitOk;
}
