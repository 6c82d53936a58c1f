// The telemetry's DDS side, private to the module: a participant in the test's domain with the
// two topics, the QoS of both ends, the partition and the copies between telemetry_frame.h's
// types and the idlc-generated wire types (same field names, std::array here, C arrays there).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

#include "rpsd/telemetry/telemetry_frame.h"
#include "rpsd/transport/dds_entity.h"
#include "rpsd/transport/dds_participant.h"
#include "rpsd_telemetry.h"

namespace rpsd::telemetry {

static_assert(rpsd_telemetry_MAX_CHANNELS == transport::kMaxChannels);
static_assert(rpsd_telemetry_SAMPLES_PER_BATCH == kSamplesPerBatch);
static_assert(rpsd_telemetry_TEXT_BYTES == kTextBytes);
static_assert(rpsd_telemetry_NAME_BYTES == sizeof(TelemetryStatus::test_name));

// Batches kept for a monitor that joins mid-test: 80 of 32 samples are 10 s at 256 samples/s.
inline constexpr int kBatchHistory = 80;
// Events kept (runs started and ended, limits, node states, operator commands): a test has a
// handful; a node that flaps may have more, and the newest are the ones to keep.
inline constexpr int kEventHistory = 256;
// How soon a subscriber sees a publisher gone (liveliness lease).
inline constexpr double kLivelinessLeaseS = 1.0;

// "rpsd/test-<id>/telemetry": beside the sites' partitions of the same test.
std::string telemetry_partition_name(std::uint32_t test_id);

// One participant with the two topics, created once.
class TelemetryParticipant {
 public:
  TelemetryParticipant(std::uint32_t domain_id, const std::string& dds_config);
  dds_entity_t get() const { return participant_.get(); }
  dds_entity_t batch_topic() const { return batch_topic_.get(); }
  dds_entity_t event_topic() const { return event_topic_.get(); }

 private:
  transport::DdsParticipant participant_;
  transport::DdsEntity batch_topic_, event_topic_;
};

// Publisher/subscriber QoS with the test's partition.
transport::DdsQos telemetry_partition_qos(std::uint32_t test_id);
// Reliable, transient-local, keep-last `depth`, never blocking the writer (docs/telemetry.md).
transport::DdsQos telemetry_qos(int depth);

void to_wire(const TelemetryBatch& in, rpsd_telemetry_Batch& out);
void from_wire(const rpsd_telemetry_Batch& in, TelemetryBatch& out);
void to_wire(const TelemetryEvent& in, rpsd_telemetry_Event& out);
void from_wire(const rpsd_telemetry_Event& in, TelemetryEvent& out);

}  // namespace rpsd::telemetry
