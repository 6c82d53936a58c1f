// Where `rpsd monitor` reads a test's telemetry from: the test's DDS partition in a run
// (dds_telemetry_source.h, over telemetry::TelemetrySubscriber), a recorded output folder
// replayed in the tests (recorded_telemetry_source.h). The server reads it from one thread.
#pragma once

#include <chrono>
#include <cstddef>
#include <vector>

#include "rpsd/telemetry/telemetry_frame.h"

namespace rpsd::monitor {

class TelemetrySource {
 public:
  virtual ~TelemetrySource() = default;
  // Appends what arrived since the last call, batches by sequence and events as they
  // happened; returns how many of both. Never blocks.
  virtual std::size_t take(std::vector<telemetry::TelemetryBatch>& batches,
                           std::vector<telemetry::TelemetryEvent>& events) = 0;
  // Waits until something is there to take, at most `timeout`; true if something is.
  virtual bool wait(std::chrono::milliseconds timeout) = 0;
  // A publisher is there and its link holds (false before a run starts and after it ends).
  virtual bool alive() const = 0;
};

}  // namespace rpsd::monitor
