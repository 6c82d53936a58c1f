// The servo node's side of a site connection over Cyclone DDS: it takes commands and
// publishes feedback and heartbeats. It does not judge commands (test id, site id, run,
// writer, step): the node's controller does, and counts what it drops.
#pragma once

#include <cstdint>

#include "rpsd/transport/dds_qos_profile.h"
#include "rpsd/transport/dds_site_ports.h"
#include "rpsd/transport/messages.h"

namespace rpsd::transport {

struct DdsNodeEndpointConfig {
  std::uint32_t test_id = 1;
  std::uint32_t site_id = 1;
  DdsQosConfig qos;
};

class DdsNodeEndpoint {
 public:
  // Not real-time safe; throws DdsError.
  DdsNodeEndpoint(const DdsParticipant& participant, const DdsNodeEndpointConfig& config);

  // Blocks until a command is waiting or the absolute CLOCK_MONOTONIC deadline passes.
  // Real-time safe.
  bool wait_for_command_until(std::int64_t deadline_ns) const { return ports_.wait_for_data_until(deadline_ns); }
  // Takes the oldest waiting command, with the writer that sent it; false when there is none.
  // Real-time safe.
  bool take_command(CommandSample& command);
  // Real-time safe (Cyclone serialises the sample).
  bool publish(const FeedbackSample& feedback);
  // Not on the fast path; a few times a second. coordinator_matched is this endpoint's own
  // (the coordinator waits for it before its first command), whatever `heartbeat` says.
  bool publish_heartbeat(const NodeHeartbeat& heartbeat);
  // Calls on_arrival(context) on Cyclone's receive thread whenever commands arrive (a
  // data-available listener), so that a lock-step node answers a command without waking
  // another thread: one thread hand-off less per exchange. nullptr stops the calls, after
  // waiting for one in progress. Not real-time safe; not from inside on_arrival.
  void call_on_command_arrival(void (*on_arrival)(void*), void* context);
  // True while a coordinator of this test and site is discovered.
  bool coordinator_matched() const { return ports_.peer_matched(); }

 private:
  DdsNodeEndpointConfig config_;
  DdsSitePorts ports_;
  DdsEntity heartbeat_publisher_, heartbeat_writer_;
  void (*on_arrival_)(void*) = nullptr;
  void* arrival_context_ = nullptr;
};

}  // namespace rpsd::transport
