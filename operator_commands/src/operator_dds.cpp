#include "operator_dds.h"

#include <stdexcept>

#include "rpsd/operator_commands/operator_command_sender.h"
#include "rpsd/transport/dds_participant.h"
#include "rpsd_operator.h"

namespace rpsd::operator_commands {

OperatorParticipant::OperatorParticipant(std::uint32_t domain_id, const std::string& config_file) {
  const auto domain = static_cast<dds_domainid_t>(domain_id);
  // Another participant of this process (the test's sites) may have made the domain first.
  domain_ = transport::make_domain({domain_id, config_file});
  participant_ = transport::DdsEntity(dds_create_participant(domain, nullptr, nullptr), "dds_create_participant");
  command_topic_ = transport::DdsEntity(permitted(dds_create_topic(participant_.get(), &rpsd_operator_Command_desc,
                                                                   "rpsd_OperatorCommand", nullptr, nullptr),
                                                  "dds_create_topic(rpsd_OperatorCommand)"),
                                        "dds_create_topic(rpsd_OperatorCommand)");
  reply_topic_ = transport::DdsEntity(
      permitted(dds_create_topic(participant_.get(), &rpsd_operator_Reply_desc, "rpsd_OperatorReply", nullptr, nullptr),
                "dds_create_topic(rpsd_OperatorReply)"),
      "dds_create_topic(rpsd_OperatorReply)");
}

dds_entity_t permitted(dds_entity_t handle, const std::string& what) {
  if (handle == DDS_RETCODE_NOT_ALLOWED_BY_SECURITY) {
    throw OperatorNotPermitted(what +
                               ": DDS Security does not let this identity send operator commands (its "
                               "permissions grant no operator role)");
  }
  return handle;
}

std::string operator_partition_name(std::uint32_t test_id) {
  return "rpsd/test-" + std::to_string(test_id) + "/operator";
}

transport::DdsQos operator_partition_qos(std::uint32_t test_id) {
  transport::DdsQos q;
  dds_qset_partition1(q.get(), operator_partition_name(test_id).c_str());
  return q;
}

transport::DdsQos command_qos() {
  transport::DdsQos q;
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 16);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  return q;
}

transport::DdsQos reply_qos() {
  transport::DdsQos q;
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 32);
  dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  return q;
}

}  // namespace rpsd::operator_commands
