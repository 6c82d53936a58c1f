// What `rpsd run` and rpsd.run share: the overrides in the command line's order, the refusal of
// HDF5 output for a sweep, and the outcome of a run that did not complete as its exception.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "rpsd/commands/overrides.h"
#include "rpsd/commands/run_outcome.h"
#include "rpsd/commands/run_scenario.h"
#include "rpsd/output/results_files.h"

namespace rpsd::commands {
namespace {

const std::filesystem::path kScenarios = std::filesystem::path(RPSD_TEST_SOURCE_DIR) / "examples/scenarios";

TEST(RunOverrides, RecordThenFormatThenTheHistoriesThenTheSetsInTheirOrder) {
  const auto set = parse_overrides({"output.format=csv", "structure.mass_kg=7000"});
  const auto all = run_overrides({"rec.AT2", false, "both", "decimated", "256"}, set);
  ASSERT_EQ(all.size(), 6u);
  EXPECT_EQ(all[0].origin, "--record");
  EXPECT_EQ(all[0].kind, scenarios::Override::Kind::kRecord);
  EXPECT_NE(all[0].value.find(std::filesystem::absolute("rec.AT2").string()), std::string::npos);
  EXPECT_EQ(all[1].origin, "--format");
  EXPECT_EQ(all[1].value, "both");
  EXPECT_EQ(all[2].origin, "--histories");
  EXPECT_EQ(all[2].key_path, "output.histories");
  EXPECT_EQ(all[3].origin, "--history-rate-hz");
  EXPECT_EQ(all[3].value, "256");
  // A --set of the same key comes later, so it wins.
  EXPECT_EQ(all[4].origin, "--set #1");
  EXPECT_EQ(all[4].key_path, "output.format");
  EXPECT_EQ(all[5].origin, "--set #2");
}

TEST(LoadRunScenario, ASingleTestIsNeitherASweepNorABatchNorAStudy) {
  const auto sweep = kScenarios / "elcentro-sdof-compensation-sweep.yaml";
  EXPECT_FALSE(is_single_test(load_run_scenario(sweep, {})));
  EXPECT_TRUE(is_single_test(load_run_scenario(kScenarios / "elcentro-sdof.yaml", {})));
  EXPECT_FALSE(is_single_test(load_run_scenario(kScenarios / "paper-fig7-max-gain.yaml", {})));
}

TEST(ThrowUnlessCompleted, EachOutcomeIsItsException) {
  studies::StudyRun run;
  EXPECT_NO_THROW(throw_unless_completed(run, "s.json"));
  run.reason = "stopped: stroke";
  run.recorded_in = "t.csv";
  run.result = hybrid_test::RunResult::kStopped;
  EXPECT_THROW(throw_unless_completed(run, "s.json"), TestStopped);
  run.result = hybrid_test::RunResult::kResultsNotWritten;
  EXPECT_THROW(throw_unless_completed(run, "s.json"), output::ResultsNotWritten);
  run.result = hybrid_test::RunResult::kInterrupted;
  EXPECT_THROW(throw_unless_completed(run, "s.json"), RunInterrupted);
  run.result = hybrid_test::RunResult::kNotReady;
  EXPECT_THROW(throw_unless_completed(run, "s.json"), RunNotReady);
}

}  // namespace
}  // namespace rpsd::commands
