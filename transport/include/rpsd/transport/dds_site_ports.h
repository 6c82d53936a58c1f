// The DDS entities one side of a site connection needs: a writer on one topic and a
// reader with a waitset on another, both in the site's partition. The coordinator's link
// writes commands and reads feedback; the node's endpoint does the opposite.
#pragma once

#include <cstdint>

#include "rpsd/transport/dds_entity.h"
#include "rpsd/transport/dds_participant.h"

namespace rpsd::transport {

class DdsSitePorts {
 public:
  // Not real-time safe; throws DdsError.
  DdsSitePorts(const DdsParticipant& participant, std::uint32_t test_id, std::uint32_t site_id,
               dds_entity_t write_topic, const DdsQos& write_qos, dds_entity_t read_topic, const DdsQos& read_qos);

  // Waits on the reader's data-available condition until absolute CLOCK_MONOTONIC time
  // deadline_ns. True when data is there. Real-time safe (blocks in DDS only).
  bool wait_for_data_until(std::int64_t deadline_ns) const;

  // True when the peer's reader and writer are both matched (DDS discovery finished).
  bool peer_matched() const;
  // Whether the peer's writer is alive (liveliness); false after its lease expired.
  bool peer_alive() const;

  dds_entity_t writer() const { return writer_.get(); }
  dds_entity_t reader() const { return reader_.get(); }

 private:
  DdsEntity publisher_, subscriber_, writer_, reader_, waitset_, data_available_;
};

}  // namespace rpsd::transport
