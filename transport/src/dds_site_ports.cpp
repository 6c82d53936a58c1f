#include "rpsd/transport/dds_site_ports.h"

#include "rpsd/realtime/pacer.h"
#include "rpsd/transport/dds_qos_profile.h"

namespace rpsd::transport {

DdsSitePorts::DdsSitePorts(const DdsParticipant& participant, std::uint32_t test_id, std::uint32_t site_id,
                           dds_entity_t write_topic, const DdsQos& write_qos, dds_entity_t read_topic,
                           const DdsQos& read_qos) {
  const DdsQos partition = site_partition_qos(test_id, site_id);
  publisher_ = DdsEntity(dds_create_publisher(participant.get(), partition.get(), nullptr), "dds_create_publisher");
  subscriber_ = DdsEntity(dds_create_subscriber(participant.get(), partition.get(), nullptr), "dds_create_subscriber");
  writer_ = DdsEntity(dds_create_writer(publisher_.get(), write_topic, write_qos.get(), nullptr), "dds_create_writer");
  reader_ = DdsEntity(dds_create_reader(subscriber_.get(), read_topic, read_qos.get(), nullptr), "dds_create_reader");
  waitset_ = DdsEntity(dds_create_waitset(participant.get()), "dds_create_waitset");
  data_available_ = DdsEntity(dds_create_readcondition(reader_.get(), DDS_ANY_STATE), "dds_create_readcondition");
  dds_check(dds_waitset_attach(waitset_.get(), data_available_.get(), 0), "dds_waitset_attach");
}

bool DdsSitePorts::wait_for_data_until(std::int64_t deadline_ns) const {
  const std::int64_t remaining = deadline_ns - realtime::monotonic_now_ns();
  const dds_return_t rc = dds_waitset_wait(waitset_.get(), nullptr, 0, remaining > 0 ? remaining : 0);
  return rc > 0;
}

bool DdsSitePorts::peer_matched() const {
  dds_publication_matched_status_t pub{};
  dds_subscription_matched_status_t sub{};
  if (dds_get_publication_matched_status(writer_.get(), &pub) < 0) return false;
  if (dds_get_subscription_matched_status(reader_.get(), &sub) < 0) return false;
  return pub.current_count > 0 && sub.current_count > 0;
}

bool DdsSitePorts::peer_alive() const {
  dds_liveliness_changed_status_t status{};
  if (dds_get_liveliness_changed_status(reader_.get(), &status) < 0) return false;
  return status.alive_count > 0;
}

}  // namespace rpsd::transport
