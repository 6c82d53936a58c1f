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

fs::path write_run(int rows, const std::string& bad_row = "") {
  const fs::path dir = fs::temp_directory_path() / ("rpsd-monitor-recorded-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream csv(dir / "time_history.csv");
  csv << "step,time_s,target_m_ch0,command_m_ch0,measured_m_ch0,measured_force_n_ch0,node_status,limit_flags,"
         "round_trip_s_ch0,cycle_lateness_s,feedback_age_periods\n";
  csv << std::setprecision(17);
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
