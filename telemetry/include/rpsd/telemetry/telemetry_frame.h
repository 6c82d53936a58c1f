// What a running test tells those who watch it (`rpsd monitor`, issue 31): decimated samples
// of every channel, batched, with the run's status, and the events as they happen. Plain
// fixed-size types, the interface between the coordinator's telemetry publisher (fed off the
// loop's thread) and whoever reads the telemetry topic; the DDS wire types mirror them.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

#include "rpsd/transport/messages.h"

namespace rpsd::telemetry {

inline constexpr int kSamplesPerBatch = 32;
inline constexpr std::size_t kTextBytes = 160;
inline constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

// One step of the test, as recorded (coordinator::StepRecord), per structure channel.
struct TelemetrySample {
  std::int64_t step = 0;
  double time_s = 0.0;
  std::uint8_t channels = 0;
  std::array<double, transport::kMaxChannels> target_m{};
  std::array<double, transport::kMaxChannels> command_m{};
  std::array<double, transport::kMaxChannels> measured_m{};
  std::array<double, transport::kMaxChannels> measured_force_n{};
  std::array<double, transport::kMaxChannels> round_trip_s{};
  std::uint8_t feedback_age_periods = 0;
  double cycle_lateness_s = 0.0;
  std::uint32_t node_status = 0;
  std::uint32_t limit_flags = 0;
};

enum class RunState : std::uint8_t { kStarting, kRunning, kHeld, kEnded };

// The run as a whole, at the time of the batch.
struct TelemetryStatus {
  std::uint32_t test_id = 0;
  std::uint64_t run_id = 0;
  std::array<char, 64> test_name{};
  RunState state = RunState::kStarting;
  std::int64_t steps_done = 0, steps_planned = 0;
  double control_rate_hz = 0.0;  // steps per second of test time
  bool real_time = false;
  std::uint8_t channels = 0;
  std::int64_t overruns = 0;       // real time: paced cycles that missed their deadline
  std::int64_t late_feedback = 0;  // exchanges answered by an older measurement
  std::uint8_t worst_feedback_age_periods = 0;
  std::int64_t dropped_samples = 0;  // decimated samples the publisher could not send
  // The delay theory's effective damping ratio of the first mode, predicted before the run,
  // and identified from the record once enough has passed (kUnknown until then).
  double predicted_effective_damping = kUnknown;
  double identified_effective_damping = kUnknown;
  std::array<char, kTextBytes> stopped_by{};  // once ended: why ("completed", "operator stop", ...)
};

struct TelemetryBatch {
  std::uint64_t sequence = 0;  // per run, from 0: a gap is a batch lost
  TelemetryStatus status;
  std::uint8_t count = 0;
  std::array<TelemetrySample, kSamplesPerBatch> samples{};
};

enum class EventKind : std::uint8_t { kRunStarted, kLimit, kNodeStatus, kOperatorCommand, kRunEnded };

// Something that happened at one step: a limit acting, a node changing state, an operator's
// command (who, what), the run starting or ending. Never decimated.
struct TelemetryEvent {
  std::uint32_t test_id = 0;
  std::uint64_t run_id = 0;
  EventKind kind = EventKind::kRunStarted;
  std::int64_t step = 0;
  double time_s = 0.0;
  std::int64_t wall_clock_unix_ns = 0;
  std::array<char, kTextBytes> text{};
};

}  // namespace rpsd::telemetry
