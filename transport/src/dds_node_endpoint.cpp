#include "rpsd/transport/dds_node_endpoint.h"

#include "dds_messages.h"

namespace rpsd::transport {

DdsNodeEndpoint::DdsNodeEndpoint(const DdsParticipant& participant, const DdsNodeEndpointConfig& config)
    : config_(config),
      ports_(participant, config.test_id, config.site_id, participant.feedback_topic(), stream_writer_qos(config.qos),
             participant.command_topic(), stream_reader_qos(config.qos)) {
  const DdsQos partition = site_partition_qos(config.test_id, config.site_id);
  heartbeat_publisher_ = DdsEntity(dds_create_publisher(participant.get(), partition.get(), nullptr), "dds_create_publisher");
  heartbeat_writer_ = DdsEntity(
      dds_create_writer(heartbeat_publisher_.get(), participant.heartbeat_topic(), heartbeat_qos(config.qos).get(), nullptr),
      "dds_create_writer(heartbeat)");
}

bool DdsNodeEndpoint::take_command(CommandSample& command) {
  rpsd_dds_Command wire{};
  void* samples[1] = {&wire};
  dds_sample_info_t info[1];
  while (dds_take(ports_.reader(), samples, info, 1, 1) > 0) {
    if (!info[0].valid_data) continue;
    copy_command(wire, command);
    return true;
  }
  return false;
}

bool DdsNodeEndpoint::publish(const FeedbackSample& feedback) {
  rpsd_dds_Feedback wire{};
  copy_feedback(feedback, wire);
  return dds_write(ports_.writer(), &wire) >= 0;
}

bool DdsNodeEndpoint::publish_heartbeat(const NodeHeartbeat& heartbeat) {
  rpsd_dds_NodeHeartbeat wire{};
  copy_heartbeat(heartbeat, wire);
  return dds_write(heartbeat_writer_.get(), &wire) >= 0;
}

}  // namespace rpsd::transport
