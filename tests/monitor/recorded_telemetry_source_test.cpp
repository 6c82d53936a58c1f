// A recorded run as telemetry: every row of time_history.csv in batches, in order, with the
// run's start, its limit events and its end; a malformed row is named by file and line.
#include "rpsd/monitor/recorded_telemetry_source.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <fstream>
#include <iomanip>

namespace rpsd::monitor {
namespace {

namespace fs = std::filesystem;

// An empty output folder named for this process, and its time_history.csv with the header.
fs::path fresh_folder(const std::string& name, std::ofstream& csv) {
  const fs::path dir = fs::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  csv.open(dir / "time_history.csv");
  csv << "step,time_s,target_m_ch0,command_m_ch0,measured_m_ch0,measured_force_n_ch0,node_status,limit_flags,"
         "round_trip_s_ch0,cycle_lateness_s,feedback_age_periods\n";
  csv << std::setprecision(17);
  return dir;
}

fs::path write_run(int rows, const std::string& bad_row = "") {
  std::ofstream csv;
  const fs::path dir = fresh_folder("rpsd-monitor-recorded", csv);
  for (int i = 1; i <= rows; ++i) {
    csv << i << ',' << i * 0.01 << ',' << i * 1e-3 << ',' << i * 1.1e-3 << ',' << i * 0.9e-3 << ',' << -5.5 * i << ','
        << 0 << ',' << (i == 40 ? 1 : 0) << ",0.0005,0," << (i % 2) << '\n';
  }
  if (!bad_row.empty()) csv << bad_row << '\n';
  std::ofstream(dir / "summary.json") << R"({"result":"stopped","stopped_by":{"reason":"operator stop"}})";
  return dir;
}

TEST(RecordedTelemetrySource, EveryRowInOrderThenTheEnd) {
  const fs::path dir = write_run(70);
  RecordedTelemetrySource source(dir, {});
  std::vector<telemetry::TelemetryBatch> batches;
  std::vector<telemetry::TelemetryEvent> events;
  source.take(batches, events);
  ASSERT_EQ(batches.size(), 3u);  // 32 + 32 + 6
  std::int64_t step = 1;
  for (const auto& b : batches) {
    for (int i = 0; i < b.count; ++i, ++step) {
      EXPECT_EQ(b.samples[i].step, step);
      EXPECT_EQ(b.samples[i].measured_m[0], step * 0.9e-3);
      EXPECT_EQ(b.samples[i].measured_force_n[0], -5.5 * step);
    }
  }
  EXPECT_EQ(step, 71);
  EXPECT_EQ(batches.back().status.state, telemetry::RunState::kEnded);
  EXPECT_EQ(batches.back().status.late_feedback, 35);
  EXPECT_EQ(std::string(batches.back().status.stopped_by.data()), "operator stop");
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].kind, telemetry::EventKind::kRunStarted);
  EXPECT_EQ(events[1].kind, telemetry::EventKind::kLimit);
  EXPECT_EQ(events[1].step, 40);
  EXPECT_EQ(events[2].kind, telemetry::EventKind::kRunEnded);
  EXPECT_FALSE(source.alive());
  fs::remove_all(dir);
}

std::vector<telemetry::TelemetrySample> rows_at(std::initializer_list<std::int64_t> steps) {
  std::vector<telemetry::TelemetrySample> rows;
  for (const std::int64_t step : steps) {
    telemetry::TelemetrySample s;
    s.step = step;
    rows.push_back(s);
  }
  return rows;
}

TEST(RecordedTelemetrySource, TheReplayIsPacedByStepsNotRows) {
  const auto every = rows_at({1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  EXPECT_EQ(rows_due(every, 0.0), 0u);
  EXPECT_EQ(rows_due(every, 0.99), 0u);
  EXPECT_EQ(rows_due(every, 1.0), 1u);
  EXPECT_EQ(rows_due(every, 4.5), 4u);
  EXPECT_EQ(rows_due(every, 100.0), 10u);
  // Every 16th step kept: a row every 16 steps of the replay, not every step.
  const auto sixteenth = rows_at({16, 32, 48, 64});
  EXPECT_EQ(rows_due(sixteenth, 1.0), 1u);
  EXPECT_EQ(rows_due(sixteenth, 16.9), 1u);
  EXPECT_EQ(rows_due(sixteenth, 17.0), 2u);
  EXPECT_EQ(rows_due(sixteenth, 48.0), 3u);
  EXPECT_EQ(rows_due(sixteenth, 49.0), 4u);
  EXPECT_EQ(rows_due({}, 5.0), 0u);
}

TEST(RecordedTelemetrySource, ADecimatedHistoryReportsTheRunsStepsRateAndCounts) {
  fs::path dir;
  {
    std::ofstream csv;
    dir = fresh_folder("rpsd-monitor-decimated", csv);
    for (int k = 1; k <= 50; ++k)
      csv << 16 * k << ',' << 16 * k / 1024.0 << ",0,0,0,0,0,0,0.0005,0," << (k == 3) << '\n';
    std::ofstream(dir / "summary.json") << R"({"result":"completed","histories":{"kept":"decimated","every_steps":16},)"
                                        << R"("timing":{"overruns":7,"late_feedback":123}})";
  }
  RecordedTelemetrySource source(dir, {});
  std::vector<telemetry::TelemetryBatch> batches;
  std::vector<telemetry::TelemetryEvent> events;
  source.take(batches, events);
  ASSERT_EQ(batches.size(), 2u);  // 32 + 18 rows
  EXPECT_EQ(batches.front().status.steps_done, 16 * 32);
  EXPECT_EQ(batches.front().status.late_feedback, 1);  // mid-replay: what the rows show
  const telemetry::TelemetryStatus& end = batches.back().status;
  EXPECT_EQ(end.state, telemetry::RunState::kEnded);
  EXPECT_EQ(end.steps_done, 800);
  EXPECT_EQ(end.steps_planned, 800);
  EXPECT_DOUBLE_EQ(end.control_rate_hz, 1024.0);
  EXPECT_EQ(end.overruns, 7);  // the run's, from summary.json
  EXPECT_EQ(end.late_feedback, 123);
  fs::remove_all(dir);
}

TEST(RecordedTelemetrySource, AMalformedRowIsNamedByFileAndLine) {
  const fs::path dir = write_run(3, "4,0.04,x,0,0,0,0,0,0,0,0");
  try {
    read_time_history(dir / "time_history.csv");
    FAIL() << "a malformed row was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("time_history.csv:5: target_m_ch0 is not a number: x"), std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rpsd::monitor
