// The QoS of rpsd's three topics, in one place (the reasons are in docs/dds-transport.md):
//
//   topic        reliability  history      durability       deadline            liveliness
//   Command      reliable     keep last 8  volatile         k control periods   automatic, lease L
//   Feedback     reliable     keep last 8  volatile         k control periods   automatic, lease L
//   Heartbeat    reliable     keep last 1  transient-local  -                   automatic, lease L
//
// Reliable with keep-last never blocks the writer on a slow or dead reader (old samples are
// replaced), yet repairs a lost packet when there is time. The deadline makes a silent peer
// visible as a status within k periods; the coordinator and the node also count missing
// periods themselves, which is what stops a test. Partitions "rpsd/test-<id>/site-<id>"
// keep two tests on one network, and two sites of one test, from ever crossing.
#pragma once

#include <cstdint>
#include <string>

#include "rpsd/transport/dds_entity.h"

namespace rpsd::transport {

struct DdsQosSettings {
  double control_period_s = 1.0 / 1024.0;
  int deadline_periods = 5;          ///< k
  double liveliness_lease_s = 1.0;   ///< L
  int history_depth = 8;
};

DdsQos command_qos(const DdsQosSettings& s);
DdsQos feedback_qos(const DdsQosSettings& s);
DdsQos heartbeat_qos(const DdsQosSettings& s);
/// Publisher/subscriber QoS carrying the partition of one site of one test.
DdsQos site_partition_qos(std::uint32_t test_id, std::uint32_t site_id);
std::string site_partition_name(std::uint32_t test_id, std::uint32_t site_id);

}  // namespace rpsd::transport
