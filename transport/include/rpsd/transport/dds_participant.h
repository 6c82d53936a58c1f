// One DDS participant of rpsd with the three topics created once. A Cyclone XML
// configuration (transport/config/*.xml) may be given; otherwise CYCLONEDDS_URI or
// Cyclone's defaults apply.
#pragma once

#include <cstdint>
#include <string>

#include "rpsd/transport/dds_entity.h"

namespace rpsd::transport {

struct DdsDomainConfig {
  std::uint32_t domain_id = 0;
  std::string config_file;  // Cyclone XML; empty: CYCLONEDDS_URI or the defaults
};

// The domain of `config` made with its Cyclone XML, owned by the entity returned; an empty
// entity when no file is named (CYCLONEDDS_URI or the defaults) or when another participant of
// this process made the domain first (it is reused). Not real-time safe; throws DdsError or
// std::runtime_error naming an unreadable file.
DdsEntity make_domain(const DdsDomainConfig& config);

class DdsParticipant {
 public:
  // Not real-time safe; throws DdsError naming the failing call, or std::runtime_error
  // naming an unreadable configuration file.
  explicit DdsParticipant(const DdsDomainConfig& config);

  dds_entity_t get() const { return participant_.get(); }
  dds_entity_t command_topic() const { return command_topic_.get(); }
  dds_entity_t feedback_topic() const { return feedback_topic_.get(); }
  dds_entity_t heartbeat_topic() const { return heartbeat_topic_.get(); }

 private:
  DdsEntity domain_;  // only when created here with an explicit configuration
  DdsEntity participant_;
  DdsEntity command_topic_, feedback_topic_, heartbeat_topic_;
};

}  // namespace rpsd::transport
