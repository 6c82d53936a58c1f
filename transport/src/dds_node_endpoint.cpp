#include "rpsd/transport/dds_node_endpoint.h"

#include "dds_messages.h"

namespace rpsd::transport {

DdsNodeEndpoint::DdsNodeEndpoint(const DdsParticipant& participant, const DdsNodeEndpointConfig& config)
    : config_(config),
      ports_(participant, config.test_id, config.site_id, participant.feedback_topic(), stream_writer_qos(config.qos),
             participant.command_topic(), stream_reader_qos(config.qos)) {
  const DdsQos partition = site_partition_qos(config.test_id, config.site_id);
  heartbeat_publisher_ =
      DdsEntity(dds_create_publisher(participant.get(), partition.get(), nullptr), "dds_create_publisher");
  heartbeat_writer_ = DdsEntity(dds_create_writer(heartbeat_publisher_.get(), participant.heartbeat_topic(),
                                                  heartbeat_qos(config.qos).get(), nullptr),
                                "dds_create_writer(heartbeat)");
}

bool DdsNodeEndpoint::take_command(CommandSample& command) {
  rpsd_dds_Command wire{};
  void* samples[1] = {&wire};
  dds_sample_info_t info[1];
  while (dds_take(ports_.reader(), samples, info, 1, 1) > 0) {
    if (!info[0].valid_data) continue;
    copy_command(wire, command);
    command.writer = info[0].publication_handle;
    return true;
  }
  return false;
}

bool DdsNodeEndpoint::publish(const FeedbackSample& feedback) {
  rpsd_dds_Feedback wire{};
  copy_feedback(feedback, wire);
  return dds_write(ports_.writer(), &wire) >= 0;
}

void DdsNodeEndpoint::call_on_command_arrival(void (*on_arrival)(void*), void* context) {
  if (!on_arrival) {
    // Waits for a listener call in progress to return (dds_set_listener does).
    dds_check(dds_set_listener(ports_.reader(), nullptr), "dds_set_listener");
    on_arrival_ = nullptr;
    arrival_context_ = nullptr;
    return;
  }
  on_arrival_ = on_arrival;
  arrival_context_ = context;
  dds_listener_t* listener = dds_create_listener(this);
  dds_lset_data_available(listener, [](dds_entity_t, void* self) {
    auto* endpoint = static_cast<DdsNodeEndpoint*>(self);
    endpoint->on_arrival_(endpoint->arrival_context_);
  });
  const dds_return_t rc = dds_set_listener(ports_.reader(), listener);
  dds_delete_listener(listener);
  dds_check(rc, "dds_set_listener");
}

bool DdsNodeEndpoint::publish_heartbeat(const NodeHeartbeat& heartbeat) {
  rpsd_dds_NodeHeartbeat wire{};
  copy_heartbeat(heartbeat, wire);
  wire.coordinator_matched = ports_.peer_matched();
  return dds_write(heartbeat_writer_.get(), &wire) >= 0;
}

}  // namespace rpsd::transport
