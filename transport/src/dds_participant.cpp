#include "rpsd/transport/dds_participant.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "rpsd_messages.h"

namespace rpsd::transport {

namespace {
std::string read_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the Cyclone DDS configuration");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}
}  // namespace

DdsEntity make_domain(const DdsDomainConfig& config) {
  if (config.config_file.empty()) return {};
  const std::string xml = read_config(config.config_file);
  const dds_entity_t domain = dds_create_domain(static_cast<dds_domainid_t>(config.domain_id), xml.c_str());
  // A second participant of this process in the same domain reuses the domain.
  if (domain == DDS_RETCODE_PRECONDITION_NOT_MET) return {};
  return DdsEntity(domain, "dds_create_domain(" + config.config_file + ")");
}

DdsParticipant::DdsParticipant(const DdsDomainConfig& config) {
  const auto domain_id = static_cast<dds_domainid_t>(config.domain_id);
  domain_ = make_domain(config);
  participant_ = DdsEntity(dds_create_participant(domain_id, nullptr, nullptr), "dds_create_participant");
  command_topic_ =
      DdsEntity(dds_create_topic(participant_.get(), &rpsd_dds_Command_desc, "rpsd_Command", nullptr, nullptr),
                "dds_create_topic(rpsd_Command)");
  feedback_topic_ =
      DdsEntity(dds_create_topic(participant_.get(), &rpsd_dds_Feedback_desc, "rpsd_Feedback", nullptr, nullptr),
                "dds_create_topic(rpsd_Feedback)");
  heartbeat_topic_ = DdsEntity(
      dds_create_topic(participant_.get(), &rpsd_dds_NodeHeartbeat_desc, "rpsd_NodeHeartbeat", nullptr, nullptr),
      "dds_create_topic(rpsd_NodeHeartbeat)");
}

}  // namespace rpsd::transport
