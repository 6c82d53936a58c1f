#include "rpsd/commands/run_outcome.h"

#include "rpsd/output/results_files.h"

namespace rpsd::commands {

void throw_unless_completed(const studies::StudyRun& run, const std::filesystem::path& summary) {
  switch (run.result) {
    case hybrid_test::RunResult::kCompleted:
      return;
    case hybrid_test::RunResult::kStopped:
      throw TestStopped(run.recorded_in, run.reason);
    case hybrid_test::RunResult::kResultsNotWritten:
      throw output::ResultsNotWritten(run.reason + "; " + summary.string() + " says what is missing");
    case hybrid_test::RunResult::kInterrupted:
      throw RunInterrupted(summary.string(), run.reason);
    case hybrid_test::RunResult::kNotReady:
      throw RunNotReady(summary.string(), run.reason);
  }
}

}  // namespace rpsd::commands
