// Those who watch a test as it runs, none of them on the loop's thread: the terminal's
// progress of a real-time run (steps, time left, overruns, the worst feedback age, from the
// recorder's writer thread) and, when the scenario asks for it, the test's telemetry for
// `rpsd monitor` (docs/telemetry.md). Built before the run, told when it started and ended.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string_view>

#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/hybrid_test/progress.h"
#include "rpsd/telemetry/telemetry_publisher.h"

namespace rpsd::hybrid_test {

// A real-time run's progress, from each record the writer takes: every ~0.5 s of wall time,
// the steps done, the loop's overruns (LiveCounters) and the oldest feedback used so far. As
// fast as possible the loop reports its own progress and this one stays silent.
class RealTimeProgress final : public coordinator::RecordObserver {
 public:
  RealTimeProgress(ProgressSink sink, std::size_t case_number, std::size_t cases);
  // The calling thread, before the first step.
  void start(std::int64_t steps_planned, bool real_time, const coordinator::LiveCounters* live);
  void observe(const coordinator::StepRecord& record) override;

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr auto kEvery = std::chrono::milliseconds(500);
  ProgressSink sink_;
  std::size_t case_number_, cases_;
  std::int64_t planned_ = 0;
  bool real_time_ = false;
  const coordinator::LiveCounters* live_ = nullptr;
  int worst_age_ = 0;
  Clock::time_point last_report_{};
};

class RunWatchers {
 public:
  // Throws what joining the test's DDS domain throws (telemetry on only). Not real-time safe.
  RunWatchers(const TestConfig& test, const ProgressSink& progress, std::size_t case_number, std::size_t cases);
  // Publishes "run ended: the run did not finish" if ended() was never called.
  ~RunWatchers();
  RunWatchers(const RunWatchers&) = delete;
  RunWatchers& operator=(const RunWatchers&) = delete;

  // For run_test_and_reference: the observers and what to do once the test is built.
  RunWatch watch();
  // The run is over: why it ended, in the summary's words.
  void ended(const TestRun& test, std::string_view outcome);
  // The telemetry publisher (operators' command events go through it); null when off.
  telemetry::TelemetryPublisher* telemetry() { return telemetry_.get(); }

 private:
  const TestConfig& test_;
  RealTimeProgress progress_;
  std::unique_ptr<telemetry::TelemetryPublisher> telemetry_;
  bool started_ = false, ended_ = false;
};

}  // namespace rpsd::hybrid_test
