// The QoS of rpsd's three topics, in one place (the reasons are in docs/dds-transport.md):
//
//   topic        reliability                 history      durability       liveliness
//   Command      reliable; real time: b. e.  keep last 8  volatile         automatic, lease L
//   Feedback     reliable; real time: b. e.  keep last 8  volatile         automatic, lease L
//   Heartbeat    reliable                    keep last 1  transient-local  automatic, lease L
//
// Lock-step: reliable with keep-last never blocks the writer on a slow or dead reader (old
// samples are replaced), yet repairs a lost packet. Real time: writers and readers are best
// effort. A reliable reader delivers in order, so one lost packet would hold back every newer
// sample until its repair (a NACK round, milliseconds), while a real-time loop wants the
// newest sample now. A best-effort reader of a reliable writer is not enough: Cyclone 0.10
// then did not deliver the samples that follow a lost one for about 3 ms, so one lost packet
// made 2 to 4 late steps instead of one, and at 5 % loss the test stopped within seconds
// (tests/system/netns_packet_loss.sh). A best-effort writer does not match a reliable reader:
// the coordinator and its nodes must run in the same mode (real time with real_time nodes,
// as fast as possible with lock_step nodes). No DDS deadline: a requested
// deadline shorter than the offered one (a node faster than its coordinator) would stop the
// endpoints from matching at all; instead the coordinator and the node count missing
// control periods themselves, which is what stops a test or makes a node hold, within k
// periods. The liveliness lease L tells a dead peer from a slow one in lock-step; in real
// time the feedback's age decides, since L lapses after any host stall longer than L. Partitions
// "rpsd/test-<id>/site-<id>" keep two tests on one network, and two sites of one test, from
// ever crossing.
#pragma once

#include <cstdint>
#include <string>

#include "rpsd/transport/dds_entity.h"

namespace rpsd::transport {

struct DdsQosSettings {
  double control_period_s = 1.0 / 1024.0;
  double liveliness_lease_s = 1.0;  // L
  int history_depth = 8;
  // Real time: readers take what arrives and writers never send repairs (best effort both).
  bool newest_only = false;
};

// Command and feedback writers and readers: reliable, or best effort with newest_only.
DdsQos stream_writer_qos(const DdsQosSettings& s);
DdsQos stream_reader_qos(const DdsQosSettings& s);
DdsQos heartbeat_qos(const DdsQosSettings& s);
// Publisher/subscriber QoS carrying the partition of one site of one test.
DdsQos site_partition_qos(std::uint32_t test_id, std::uint32_t site_id);
std::string site_partition_name(std::uint32_t test_id, std::uint32_t site_id);

}  // namespace rpsd::transport
