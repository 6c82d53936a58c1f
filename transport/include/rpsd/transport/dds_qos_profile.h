// The QoS of rpsd's three topics, in one place so that both ends of every topic always match:
//   topic        reliability                 history      durability       liveliness
//   Command      reliable; real time: b. e.  keep last 8  volatile         automatic, lease L
//   Feedback     reliable; real time: b. e.  keep last 8  volatile         automatic, lease L
//   Heartbeat    reliable                    keep last 1  transient-local  automatic, lease L
// and one partition "rpsd/test-<id>/site-<id>" per site of a test. Why each choice (best effort at both ends
// in real time, no DDS deadline, what L decides): docs/dds-transport.md, "QoS of the three topics".
#pragma once

#include <cstdint>
#include <string>

#include "rpsd/transport/dds_entity.h"

namespace rpsd::transport {

struct DdsQosConfig {
  double control_period_s = 1.0 / 1024.0;
  double liveliness_lease_s = 1.0;  // L
  int history_depth = 8;
  // Real time: readers take what arrives and writers never send repairs (best effort both).
  bool newest_only = false;
};
using DdsQosSettings [[deprecated("renamed DdsQosConfig (docs/migration.md)")]] = DdsQosConfig;

// Command and feedback writers and readers: reliable, or best effort with newest_only.
DdsQos stream_writer_qos(const DdsQosConfig& s);
DdsQos stream_reader_qos(const DdsQosConfig& s);
DdsQos heartbeat_qos(const DdsQosConfig& s);
// Publisher/subscriber QoS carrying the partition of one site of one test.
DdsQos site_partition_qos(std::uint32_t test_id, std::uint32_t site_id);
std::string site_partition_name(std::uint32_t test_id, std::uint32_t site_id);

}  // namespace rpsd::transport
