// The coordinator's link to one site (one servo node) over Cyclone DDS. send() publishes the
// step's command; receive() waits on a waitset for the feedback of that step.
//
// Lock-step (as fast as possible over the real link): receive() waits up to
// feedback_timeout_s for the feedback of exactly the step sent, polling for busy_wait_s first.
// Real time: the coordinator sets a receive deadline each cycle; feedback that has not come
// by then is late — receive() returns kTimeout and hands back the newest feedback the node
// sent (if any), so the caller decides whether to carry on with it and counts it.
#pragma once

#include <array>
#include <cstdint>

#include "rpsd/transport/dds_qos_profile.h"
#include "rpsd/transport/dds_site_ports.h"
#include "rpsd/transport/link.h"

namespace rpsd::transport {

struct DdsLinkConfig {
  std::uint32_t test_id = 1;
  std::uint32_t site_id = 1;
  int channels = 1;
  DdsQosSettings qos;
  double feedback_timeout_s = 1.0;  // longest wait for one step's feedback
  // Lock-step only: poll the reader this long before sleeping on the waitset, so the feedback is
  // picked up without this thread being woken, at the cost of a busy core while the node works.
  // 0: never. Measured effect: docs/dds-transport.md.
  double busy_wait_s = 0.0;
};

// Messages the link refused to use, by reason.
struct DdsLinkCounters {
  std::int64_t sent = 0, received = 0;
  std::int64_t wrong_test_or_site = 0, wrong_channels = 0, older_step = 0;
  std::int64_t late = 0;
  std::int64_t waits = 0;  // receives that slept on the waitset (the feedback was not in yet)
};

class DdsLink final : public Link {
 public:
  // Not real-time safe; throws DdsError or std::invalid_argument.
  DdsLink(const DdsParticipant& participant, const DdsLinkConfig& config);

  // Waits until the site's node is discovered both ways on this side and its heartbeat says
  // it has discovered this coordinator too; only then does the first command reach it.
  // Not real-time safe.
  bool wait_for_node(double timeout_s);

  // Real-time safe (no allocation in rpsd's code; Cyclone serialises the sample).
  LinkStatus send(const CommandSample& command) override;
  // Real-time safe.
  LinkStatus receive(FeedbackSample& feedback) override;

  // Real time: absolute CLOCK_MONOTONIC time by which receive() gives up (0: none).
  void set_receive_deadline_ns(std::int64_t deadline_ns) { receive_deadline_ns_ = deadline_ns; }

  const DdsLinkCounters& counters() const { return counters_; }

 private:
  // Takes every sample waiting; keeps the newest valid one in newest_, except that a sample
  // reporting a node fault or a non-finite measurement stays there once taken, so the loop
  // stops on it even when newer answers came before it looked. Real-time safe.
  void drain();

  // Takes the heartbeats waiting; true when the newest says the node has matched us.
  bool node_reports_matched();

  DdsLinkConfig config_;
  DdsSitePorts ports_;
  DdsEntity heartbeat_subscriber_, heartbeat_reader_;
  bool node_matched_ = false;
  std::int64_t sent_step_ = -1;
  std::int64_t sent_at_ns_ = 0;
  std::int64_t receive_deadline_ns_ = 0;
  FeedbackSample newest_;
  bool have_newest_ = false;
  bool holding_alarm_ = false;
  std::int64_t newest_at_ns_ = 0;
  DdsLinkCounters counters_;
};

}  // namespace rpsd::transport
