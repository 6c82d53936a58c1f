// The live source: the test's telemetry topics in its DDS partition, read by a participant
// of the monitor's own that never writes a sample (telemetry::TelemetrySubscriber).
#pragma once

#include "rpsd/monitor/telemetry_source.h"
#include "rpsd/telemetry/telemetry_subscriber.h"

namespace rpsd::monitor {

class DdsTelemetrySource final : public TelemetrySource {
 public:
  // Joins the domain and the test's partition; throws as TelemetrySubscriber does.
  explicit DdsTelemetrySource(const telemetry::TelemetrySubscriberConfig& config) : subscriber_(config) {}

  std::size_t take(std::vector<telemetry::TelemetryBatch>& batches,
                   std::vector<telemetry::TelemetryEvent>& events) override {
    return subscriber_.take(batches, events);
  }
  bool wait(std::chrono::milliseconds timeout) override { return subscriber_.wait(timeout); }
  bool alive() const override { return subscriber_.publisher_alive(); }

 private:
  telemetry::TelemetrySubscriber subscriber_;
};

}  // namespace rpsd::monitor
