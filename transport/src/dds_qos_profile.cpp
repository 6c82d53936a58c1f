#include "rpsd/transport/dds_qos_profile.h"

#include <cmath>

namespace rpsd::transport {

namespace {

dds_duration_t seconds(double s) { return static_cast<dds_duration_t>(std::llround(s * 1e9)); }

DdsQos stream_qos(const DdsQosConfig& s, dds_reliability_kind_t reliability) {
  DdsQos q;
  dds_qset_reliability(q.get(), reliability, DDS_MSECS(1));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, s.history_depth);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_liveliness(q.get(), DDS_LIVELINESS_AUTOMATIC, seconds(s.liveliness_lease_s));
  dds_qset_latency_budget(q.get(), 0);
  return q;
}

}  // namespace

DdsQos stream_writer_qos(const DdsQosConfig& s) {
  return stream_qos(s, s.newest_only ? DDS_RELIABILITY_BEST_EFFORT : DDS_RELIABILITY_RELIABLE);
}
DdsQos stream_reader_qos(const DdsQosConfig& s) {
  return stream_qos(s, s.newest_only ? DDS_RELIABILITY_BEST_EFFORT : DDS_RELIABILITY_RELIABLE);
}

DdsQos heartbeat_qos(const DdsQosConfig& s) {
  DdsQos q;
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_MSECS(10));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_liveliness(q.get(), DDS_LIVELINESS_AUTOMATIC, seconds(s.liveliness_lease_s));
  return q;
}

std::string site_partition_name(std::uint32_t test_id, std::uint32_t site_id) {
  return "rpsd/test-" + std::to_string(test_id) + "/site-" + std::to_string(site_id);
}

DdsQos site_partition_qos(std::uint32_t test_id, std::uint32_t site_id) {
  DdsQos q;
  dds_qset_partition1(q.get(), site_partition_name(test_id, site_id).c_str());
  return q;
}

}  // namespace rpsd::transport
