// What the telemetry tests share: a loopback DDS domain of their own (one per test process,
// so parallel ctest processes never meet), and collecting what a subscriber gets until a
// run's end has arrived.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "claimed_dds_domain.h"
#include "rpsd/telemetry/telemetry_subscriber.h"

namespace rpsd::telemetry::testing {

inline std::uint32_t test_domain() { return ::rpsd::testing::claimed_dds_domain(); }
inline std::string loopback_xml() { return std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/loopback.xml"; }

struct Received {
  std::vector<TelemetryBatch> batches;
  std::vector<TelemetryEvent> events;
  bool ended() const { return !events.empty() && events.back().kind == EventKind::kRunEnded; }
};

// Takes until the run-ended event and the batch with the ended status arrived (a hang guard of
// 30 s, never a measure of anything).
inline Received collect_until_ended(TelemetrySubscriber& subscriber) {
  Received r;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  const auto ended_batch = [&] { return !r.batches.empty() && r.batches.back().status.state == RunState::kEnded; };
  while (!(r.ended() && ended_batch()) && std::chrono::steady_clock::now() < give_up) {
    subscriber.wait(std::chrono::milliseconds(100));
    subscriber.take(r.batches, r.events);
  }
  return r;
}

// Waits until the subscriber has matched a live publisher (hang guard 30 s).
inline bool wait_for_publisher(const TelemetrySubscriber& subscriber) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!subscriber.publisher_alive()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    ::usleep(10'000);
  }
  return true;
}

}  // namespace rpsd::telemetry::testing
