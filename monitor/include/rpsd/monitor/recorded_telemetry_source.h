// A recorded test as telemetry: the rows of an output folder's time_history.csv published as
// batches (every row it holds: every step, or every k-th of a decimated history), with the
// run's start, its limit events (a row whose limit_flags or node_status changes) and its end
// from summary.json. The replay is paced by the rows' step numbers, so a decimated history
// replays at the run's own speed, and its end reports the run's overruns and late feedback
// from summary.json (the rows hold only some of them). It stands in for a
// running test where there is none: the monitor's browser tests, a demonstration.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "rpsd/monitor/telemetry_source.h"

namespace rpsd::monitor {

struct RecordedRunOptions {
  std::uint32_t test_id = 1;
  std::uint64_t run_id = 1;
  double steps_per_second = 0.0;  // wall-clock pace of the replay; 0: everything at once
  double predicted_effective_damping = telemetry::kUnknown;
};

// How many of `rows` (in step order) fall within the first `steps_elapsed` steps of the
// replay, counted from the first row's step: with every step recorded, floor(steps_elapsed).
std::size_t rows_due(const std::vector<telemetry::TelemetrySample>& rows, double steps_elapsed);

// The samples of a time_history.csv. Throws std::runtime_error naming the file, line and
// column that cannot be read.
std::vector<telemetry::TelemetrySample> read_time_history(const std::filesystem::path& csv);

class RecordedTelemetrySource final : public TelemetrySource {
 public:
  // Reads folder/time_history.csv and, when there, folder/summary.json (its stop reason).
  RecordedTelemetrySource(const std::filesystem::path& folder, RecordedRunOptions options);

  std::size_t take(std::vector<telemetry::TelemetryBatch>& batches,
                   std::vector<telemetry::TelemetryEvent>& events) override;
  bool wait(std::chrono::milliseconds timeout) override;
  bool alive() const override;

  std::size_t steps() const { return samples_.size(); }

 private:
  std::size_t due_samples() const;  // how many the pace has released by now

  RecordedRunOptions options_;
  std::vector<telemetry::TelemetrySample> samples_;
  std::string stopped_by_;
  std::string test_name_;
  std::chrono::steady_clock::time_point started_;
  mutable std::mutex mutex_;
  std::size_t sent_ = 0;
  std::uint64_t sequence_ = 0;
  bool start_sent_ = false, end_sent_ = false;
  std::uint32_t last_limit_flags_ = 0, last_node_status_ = 0;
  std::uint8_t worst_age_ = 0;
  std::int64_t overruns_ = 0, late_feedback_ = 0;
  // A decimated history's run totals from summary.json (timing), reported at the end; -1: none.
  std::int64_t run_overruns_ = -1, run_late_feedback_ = -1;
};

}  // namespace rpsd::monitor
