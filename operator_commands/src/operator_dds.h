// The DDS side shared by the sender and the listener: a participant with the two operator
// topics, and their QoS. Commands are reliable and volatile (the sender repeats until it is
// answered, so none waits for a later run); replies are reliable and transient-local, so a
// sender whose reader was discovered after the reply was written still receives it.
#pragma once

#include <cstdint>
#include <string>

#include "rpsd/transport/dds_entity.h"

namespace rpsd::operator_commands {

class OperatorParticipant {
 public:
  // Not real-time safe; throws transport::DdsError or std::runtime_error (unreadable file).
  OperatorParticipant(std::uint32_t domain_id, const std::string& config_file);
  dds_entity_t get() const { return participant_.get(); }
  dds_entity_t command_topic() const { return command_topic_.get(); }
  dds_entity_t reply_topic() const { return reply_topic_.get(); }

 private:
  transport::DdsEntity domain_, participant_, command_topic_, reply_topic_;
};

// "rpsd/test-<id>/operator": beside the test's sites' partitions.
std::string operator_partition_name(std::uint32_t test_id);
transport::DdsQos operator_partition_qos(std::uint32_t test_id);
transport::DdsQos command_qos();
transport::DdsQos reply_qos();

}  // namespace rpsd::operator_commands
