// The recorder checks every write: a file that cannot grow (RLIMIT_FSIZE here, a full disk in
// the lab) is reported through write_failed(), and the test stops with kResultsNotWritten
// instead of completing with rows missing.
#include "rpsd/coordinator/recorder.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../servo/paper_rig.h"
#include "elcentro_study.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

// Files this process writes may not grow past `bytes` while it lives; writes beyond fail
// with EFBIG instead of raising SIGXFSZ.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit saved_{};
  void (*old_handler_)(int) = nullptr;
};

std::filesystem::path scratch(const char* name) {
  return std::filesystem::temp_directory_path() / (std::string(name) + "-" + std::to_string(getpid()) + ".csv");
}

StepRecord some_record(std::int64_t step) {
  StepRecord r;
  r.step = step;
  r.time_s = 1e-3 * static_cast<double>(step);
  r.target_m[0] = 1.2345678e-3;
  r.displacement_m[0] = -9.87654321e-4;
  return r;
}

TEST(Recorder, APacedRunsWriterPollsWithinAFifthOfItsPeriod) {
  // A row waits at most one idle poll before the writer takes it: a fifth of the period at
  // 1024 Hz (so a kill -9 loses no more than the step in flight), never above the 1 ms of a
  // run as fast as possible, never below 50 us (each wake-up may take a core from the loop).
  EXPECT_EQ(paced_idle_poll(1.0 / 1024.0).count(), 195);
  EXPECT_EQ(paced_idle_poll(1.0 / 256.0).count(), 781);
  EXPECT_EQ(paced_idle_poll(1.0 / 4096.0).count(), 50);
  EXPECT_EQ(paced_idle_poll(0.1).count(), 1000);
  EXPECT_EQ(paced_idle_poll(std::nan("")).count(), 50);
  EXPECT_EQ(RecorderOptions{}.idle_poll.count(), 1000);
  RecorderOptions none;
  none.idle_poll = std::chrono::microseconds(0);
  EXPECT_THROW(Recorder("", 1, 1, none), std::invalid_argument);
}

TEST(Recorder, AFileThatCannotGrowIsReportedWithItsNameAndTheSystemsReason) {
  const auto csv = scratch("rpsd-recorder-limit");
  std::string error;
  {
    const FileSizeLimit limit(32 * 1024);
    Recorder recorder(csv, 1, 1, {false, 64});
    for (std::int64_t n = 0; n < 5000; ++n) recorder.record_or_wait(some_record(n));
    recorder.finish();
    EXPECT_TRUE(recorder.write_failed());
    error = recorder.write_error();
  }
  EXPECT_NE(error.find(csv.string()), std::string::npos) << error;
  EXPECT_NE(error.find("File too large"), std::string::npos) << error;
  std::filesystem::remove(csv);
}

TEST(Recorder, AWholeFileIsNotAFailure) {
  const auto csv = scratch("rpsd-recorder-whole");
  Recorder recorder(csv, 1, 1, {false, 64});
  for (std::int64_t n = 0; n < 5000; ++n) recorder.record_or_wait(some_record(n));
  recorder.finish();
  EXPECT_FALSE(recorder.write_failed());
  EXPECT_EQ(recorder.write_error(), "");
  std::filesystem::remove(csv);
}

// A watcher that writes the results (results.h5) and fails after its 100th record.
class FailingWriter final : public RecordObserver {
 public:
  void observe(const StepRecord&) override { ++seen_; }
  bool failed() const override { return seen_ >= 100; }
  std::string failure() const override { return "results.h5: write failed"; }

 private:
  int seen_ = 0;
};

TEST(Recorder, AWatcherThatFailsToWriteIsAFailedWrite) {
  FailingWriter writer;
  RecorderOptions options{false, 64};
  options.observers = {&writer};
  Recorder recorder({}, 1, 1, options);
  for (std::int64_t n = 0; n < 500; ++n) recorder.record_or_wait(some_record(n));
  recorder.finish();
  EXPECT_TRUE(recorder.write_failed());
  EXPECT_EQ(recorder.write_error(), "results.h5: write failed");
}

TEST(TestAssembly, AFailedRecordStopsTheTestWithItsOwnOutcome) {
  const auto csv = scratch("rpsd-assembly-limit");
  const FileSizeLimit limit(64 * 1024);
  TestAssembly test(elcentro(), {csv, false, false, {}, nullptr});
  const StepOutcome outcome = test.run({}, {});
  const TestRun run = test.finish(outcome);
  EXPECT_EQ(run.outcome, StepOutcome::kResultsNotWritten);
  EXPECT_LT(run.steps, run.steps_planned);  // it stopped, it did not run on unrecorded
  EXPECT_NE(run.write_error.find(csv.string()), std::string::npos) << run.write_error;
  std::filesystem::remove(csv);
}

TEST(TestAssembly, AStopRequestEndsTheRunAfterTheStepUnderWay) {
  std::atomic<bool> stop{false};
  TestAssembly test(elcentro(), {{}, false, false, {}, &stop});
  std::int64_t seen = 0;
  const StepOutcome outcome = test.run(
      [&](const StepRecord&) {
        if (++seen == 100) stop.store(true);
      },
      {});
  const TestRun run = test.finish(outcome);
  EXPECT_EQ(run.outcome, StepOutcome::kInterrupted);
  EXPECT_EQ(run.steps, 100);  // the step under way is counted and recorded, no further one
}

// Counts the records it is handed.
class CountingWatcher final : public RecordObserver {
 public:
  void observe(const StepRecord&) override { ++seen; }
  int seen = 0;
};

// output.histories: decimated: the CSV keeps the rows of the steps n with n % k == 0, by exact
// step index, while the watchers (the telemetry, results.h5's writer) still see every record.
TEST(Recorder, ADecimatedCsvKeepsEveryKthStepAndTheWatchersSeeEveryRecord) {
  const auto csv = scratch("rpsd-recorder-decimated");
  CountingWatcher watcher;
  RecorderOptions options{false, 64};
  options.csv_every_steps = 8;
  options.observers = {&watcher};
  Recorder recorder(csv, 1, 1, options);
  for (std::int64_t n = 1; n <= 100; ++n) recorder.record_or_wait(some_record(n));
  recorder.finish();
  EXPECT_FALSE(recorder.write_failed());
  EXPECT_EQ(watcher.seen, 100);
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // the header
  std::vector<std::int64_t> steps;
  while (std::getline(in, line)) steps.push_back(std::stoll(line.substr(0, line.find(','))));
  std::vector<std::int64_t> expected;
  for (std::int64_t n = 8; n <= 100; n += 8) expected.push_back(n);
  EXPECT_EQ(steps, expected);
  std::filesystem::remove(csv);
}

TEST(Recorder, AKeptStepEveryZeroStepsIsRefused) {
  RecorderOptions options{false, 64};
  options.csv_every_steps = 0;
  EXPECT_THROW(Recorder(std::filesystem::path(), 1, 1, options), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::coordinator
