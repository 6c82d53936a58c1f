// The outcomes that end a run of `rpsd run` (and of rpsd.run in Python) other than its
// completion, as exceptions: apps/rpsd/main.cpp maps each to its exit code, the Python
// module to its exception class.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "rpsd/studies/study_output.h"

namespace rpsd::commands {

// The dry run found a limit exceeded, an undamped mode or an early stop (exit code 4).
struct DryRunNotReady : std::runtime_error {
  DryRunNotReady() : std::runtime_error("the dry run says the test is not ready (see above)") {}
};

// No servo node answered before the first step of a run (exit code 4): nothing moved.
struct RunNotReady : std::runtime_error {
  RunNotReady(const std::string& summary, const std::string& reason)
      : std::runtime_error("test " + reason + "; " + summary + " says so") {}
};

// A test that stopped before its end; its files are complete for every step it took (exit code 3).
struct TestStopped : std::runtime_error {
  TestStopped(const std::string& recorded_in, const std::string& reason)
      : std::runtime_error("test " + reason + "; every recorded step is in " + recorded_in) {}
};

// SIGINT or SIGTERM ended a run in order: the step under way finished and was recorded (exit code 6).
struct RunInterrupted : std::runtime_error {
  RunInterrupted(const std::string& summary, const std::string& reason)
      : std::runtime_error(reason + "; the steps taken are recorded, and " + summary + " says so") {}
};

// Throws the exception of a run that did not complete (output::ResultsNotWritten for a failed
// write); returns for a completed one. `summary` names the run's summary.json.
void throw_unless_completed(const studies::StudyRun& run, const std::filesystem::path& summary);

}  // namespace rpsd::commands
