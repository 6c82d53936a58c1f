// rpsd's exit codes: one table for every subcommand (README, "Exit codes"). CLI11's own
// codes never leave the process: a bad option is bad input like a bad file.
#pragma once

namespace rpsd::cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitInternalError = 1,  // a failure that is not the input's: a bug, the OS refused something
  kExitBadInput = 2,       // a file, key, value or option is wrong, or --out holds another run
  kExitStopped = 3,        // the test stopped before its end (limit, run-away, node or link failure)
  kExitNotReady = 4,       // not ready: the dry run says so, no servo node answered before the first step, a setup's
                           // calibration offset is beyond its limit, or a node's
                           // actuator did not start
  kExitResultsNotWritten = 5,  // a result file could not be written (full disk, permissions)
  kExitInterrupted = 6,        // SIGINT or SIGTERM ended the run in order
  kExitCommandRefused = 7,     // rpsd stop: the test answered and refused the command
  kExitNoAnswer = 8,           // rpsd stop: no test answered in time
};

}  // namespace rpsd::cli
