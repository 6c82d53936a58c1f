// The reading end of a test's telemetry (`rpsd monitor`, tests): a DDS participant of its own
// in the test's partition that reads the batch and event topics and never writes a sample.
// A subscriber that joins mid-test gets the recent past the publisher keeps (about 10 s of
// batches, every event up to a bound; docs/telemetry.md, "QoS"), and one that stops reading
// or goes away changes nothing in the test: the publisher never waits for it.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rpsd/telemetry/telemetry_frame.h"

namespace rpsd::telemetry {

// Where a test's telemetry is: its DDS domain, its Cyclone configuration and its test id
// (the partition "rpsd/test-<id>/telemetry"). With DDS Security on, the Cyclone XML names
// the identity (a monitor's certificate and permissions, docs/dds-security.md).
struct TelemetrySubscriberConfig {
  std::uint32_t domain_id = 0;
  std::string dds_config;  // Cyclone XML file; empty: CYCLONEDDS_URI or Cyclone's defaults
  std::uint32_t test_id = 1;
};

class TelemetrySubscriber {
 public:
  // Joins the domain and the test's partition. Not real-time safe; throws
  // transport::DdsError naming the failing call, or std::runtime_error naming an unreadable
  // configuration file.
  explicit TelemetrySubscriber(const TelemetrySubscriberConfig& config);
  ~TelemetrySubscriber();
  TelemetrySubscriber(const TelemetrySubscriber&) = delete;
  TelemetrySubscriber& operator=(const TelemetrySubscriber&) = delete;

  // Appends what arrived since the last call, each topic in the order it was published
  // (batches by sequence, events as they happened); returns how many of both it appended.
  // Never blocks. Batches of every run of the test come through: tell runs apart by run_id.
  std::size_t take(std::vector<TelemetryBatch>& batches, std::vector<TelemetryEvent>& events);
  // Waits until something is there to take, at most `timeout`; true if something is.
  bool wait(std::chrono::milliseconds timeout);
  // A publisher of this test is matched and its liveliness holds (false before any run
  // starts, and within about a second of one ending or losing its link).
  bool publisher_alive() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace rpsd::telemetry
