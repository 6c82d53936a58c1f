// The coordinator's link to one site (one servo node) over Cyclone DDS. send() publishes the
// step's command; receive() waits on a waitset for the feedback of that step.
//
// Lock-step (as fast as possible over the real link): receive() waits up to
// feedback_timeout_s for the feedback of exactly the step sent, polling for busy_wait_s first.
// Real time: the coordinator sets a receive deadline each cycle; feedback that has not come
// by then is late — receive() returns kTimeout and hands back the newest feedback the node
// sent (if any), so the caller decides whether to carry on with it and counts it.
//
// Identity: every command carries the link's run id; a node serves one run at a time and its
// feedback names the run it serves. The link uses only feedback of its own run, from the one
// writer that first answered it; a node that serves another run (its feedback or heartbeat
// says so) or runs at another control period refuses this run: receive() returns kRefused and
// refusal() says why.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "rpsd/transport/dds_qos_profile.h"
#include "rpsd/transport/dds_site_ports.h"
#include "rpsd/transport/link.h"

namespace rpsd::transport {

struct DdsLinkConfig {
  std::uint32_t test_id = 1;
  std::uint32_t site_id = 1;
  std::uint64_t run_id = 0;  // this run's (0: the link draws one)
  int channels = 1;
  DdsQosConfig qos;
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
  std::int64_t other_run = 0;        // feedback of another run: the node serves it, not this one
  std::int64_t unknown_writer = 0;   // feedback of this run from a writer other than its node's
  std::int64_t no_run = 0;           // feedback of a node serving no run (before it took this one)
  std::int64_t impossible_step = 0;  // feedback of a step not sent yet: no node can have answered it
  std::int64_t late = 0;
  std::int64_t waits = 0;  // receives that slept on the waitset (the feedback was not in yet)
};

// Why a site's node will not serve this run.
struct NodeRefusal {
  enum class Kind : std::uint8_t {
    kNone,
    kServingOtherRun,  // the node serves another run (serving_run_id)
    kRateMismatch,     // the node's control period (node_control_period_s) is not this run's
  };
  Kind kind = Kind::kNone;
  std::uint64_t serving_run_id = 0;
  double node_control_period_s = 0.0;
};

class DdsLink final : public Link {
 public:
  // Not real-time safe; throws DdsError or std::invalid_argument.
  DdsLink(const DdsParticipant& participant, const DdsLinkConfig& config);

  // Waits until the site's node is discovered both ways on this side and its heartbeat says
  // it has discovered this coordinator too; only then does the first command reach it.
  // False after timeout_s, or at once when the heartbeat says the node refuses this run
  // (refusal()). Not real-time safe.
  bool wait_for_node(double timeout_s);

  // The newest heartbeat heard from the site's node (nullopt: none yet). After wait_for_node
  // it carries the node's actuator reading at rest, before this run's first command, which a
  // setup's calibration uses (NodeHeartbeat::measured false: the node has read nothing yet).
  const std::optional<NodeHeartbeat>& node_heartbeat() const { return node_heartbeat_; }

  std::uint64_t run_id() const { return config_.run_id; }
  // Why the node refuses this run (kind kNone: it has not).
  const NodeRefusal& refusal() const { return refusal_; }
  // The refusal as a sentence naming the site: "site 1 is serving another run (...)". Not
  // real-time safe.
  std::string refusal_text() const;

  // What faulted the site's node, as its heartbeat says (the lab controller's own words when
  // it gave any), waiting up to wait_s for a heartbeat that says it; empty when none did. A
  // node announces its fault at once. Not real-time safe.
  std::string node_fault_text(double wait_s);

  // Tells the node the run is over, so that it may serve another at once (a node also frees
  // itself after a silence); nothing when no command was sent. Not real-time safe.
  void end_run();

  // Lock-step, while an operator holds the test: repeats the last command sent, which the
  // node takes as word that the run is alive (it frees itself from a run silent for
  // release_after_silence_s) and applies no second time. Nothing before the first command.
  // Not real-time safe (called while held, between steps).
  void keep_alive();

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

  // Takes the heartbeats waiting; true when the newest says the node has matched us. The
  // newest also says whether the node refuses this run (refusal_). Real-time safe.
  bool node_reports_matched();
  void refuse(NodeRefusal::Kind kind, std::uint64_t serving_run_id, double node_period_s);

  DdsLinkConfig config_;
  CommandSample last_command_{};  // what keep_alive() repeats
  DdsSitePorts ports_;
  DdsEntity heartbeat_subscriber_, heartbeat_reader_;
  bool node_matched_ = false;
  NodeRefusal refusal_;
  std::array<char, kFaultTextBytes> node_fault_text_{};  // from the newest faulted heartbeat
  std::optional<NodeHeartbeat> node_heartbeat_;          // the newest heard
  std::uint64_t node_writer_ = 0;                        // the writer of the first feedback of this run (0: none yet)
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
