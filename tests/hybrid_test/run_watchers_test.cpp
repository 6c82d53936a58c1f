// Watching a test changes nothing it writes: with the telemetry on, the CSV files are the
// same bytes as with it off. A real-time run's progress comes from the recorder's thread with
// the loop's overruns and the oldest feedback used; as fast as possible it stays silent.
#include "rpsd/hybrid_test/run_watchers.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "claimed_dds_domain.h"
#include "rpsd/hybrid_test/specimen_sdof.h"

namespace rpsd::hybrid_test {
namespace {

std::string read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".csv");
}

TEST(RunWatchers, TheTelemetryOnWritesTheSameCsvBytesAsOff) {
  SpecimenSdof sdof;
  sdof.duration_s = 4.0;
  sdof.ground_acceleration_m_per_s2.resize(4096);
  for (std::size_t n = 0; n < sdof.ground_acceleration_m_per_s2.size(); ++n)
    sdof.ground_acceleration_m_per_s2[n] = 2.0 * std::sin(0.02 * static_cast<double>(n));
  TestConfig config = specimen_sdof_test(sdof);
  config.transport.domain_id = ::rpsd::testing::claimed_dds_domain();
  config.transport.dds_config = std::filesystem::path(RPSD_TEST_SOURCE_DIR) / "transport/config/loopback.xml";
  config.transport.test_id = 31;
  const auto off_csv = scratch("rpsd-watch-off"), on_csv = scratch("rpsd-watch-on");
  const auto off_ref = scratch("rpsd-watch-off-ref"), on_ref = scratch("rpsd-watch-on-ref");
  {
    RunWatchers off(config, {}, 1, 1);
    ASSERT_EQ(off.telemetry(), nullptr);
    const EvaluatedTest run = run_test_and_reference(config, off_csv, off_ref, {}, nullptr, off.watch());
    off.ended(run.test, "completed");
  }
  config.telemetry.enabled = true;
  std::uint64_t sent = 0;
  {
    RunWatchers on(config, {}, 1, 1);
    ASSERT_NE(on.telemetry(), nullptr);
    const EvaluatedTest run = run_test_and_reference(config, on_csv, on_ref, {}, nullptr, on.watch());
    on.ended(run.test, "completed");
    sent = on.telemetry()->batches_sent();
  }
  EXPECT_GE(sent, 4096u / 4 / telemetry::kSamplesPerBatch);  // it did publish
  const std::string off_text = read_all(off_csv);
  EXPECT_GT(off_text.size(), 100000u);
  EXPECT_EQ(off_text, read_all(on_csv));
  EXPECT_EQ(read_all(off_ref), read_all(on_ref));
  for (const auto& f : {off_csv, on_csv, off_ref, on_ref}) std::filesystem::remove(f);
}

TEST(RealTimeProgress, ReportsStepsOverrunsAndTheWorstFeedbackAgeOfARealTimeRun) {
  std::vector<ProgressReport> reports;
  RealTimeProgress progress([&](const ProgressReport& r) { reports.push_back(r); }, 2, 3);
  coordinator::LiveCounters live;
  live.overruns.store(7);
  progress.start(10000, true, &live);
  coordinator::StepRecord r;
  r.step = 10;
  r.feedback_age_periods = 3;
  progress.observe(r);  // not a multiple of 64: the clock is not even read
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  r.step = 640;
  r.feedback_age_periods = 1;
  progress.observe(r);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].phase, "test");
  EXPECT_EQ(reports[0].done, 640);
  EXPECT_EQ(reports[0].planned, 10000);
  EXPECT_EQ(reports[0].case_number, 2u);
  EXPECT_EQ(reports[0].cases, 3u);
  EXPECT_TRUE(reports[0].real_time);
  EXPECT_EQ(reports[0].overruns, 7);
  EXPECT_EQ(reports[0].worst_feedback_age_periods, 3);  // the worst so far, not the last
}

TEST(RealTimeProgress, StaysSilentAsFastAsPossibleWhereTheLoopReportsItself) {
  int reports = 0;
  RealTimeProgress progress([&](const ProgressReport&) { ++reports; }, 1, 1);
  progress.start(10000, false, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  coordinator::StepRecord r;
  r.step = 640;
  progress.observe(r);
  EXPECT_EQ(reports, 0);
}

}  // namespace
}  // namespace rpsd::hybrid_test
