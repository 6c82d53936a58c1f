#include "rpsd/transport/dds_link.h"

#include <algorithm>
#include <stdexcept>

#include "dds_messages.h"
#include "rpsd/realtime/pacer.h"

namespace rpsd::transport {

DdsLink::DdsLink(const DdsParticipant& participant, const DdsLinkConfig& config)
    : config_(config),
      ports_(participant, config.test_id, config.site_id, participant.command_topic(), stream_writer_qos(config.qos),
             participant.feedback_topic(), stream_reader_qos(config.qos)) {
  if (config.channels < 1 || config.channels > kMaxChannels) {
    throw std::invalid_argument("DdsLink: a site has between 1 and " + std::to_string(kMaxChannels) + " channels");
  }
  if (!(config.feedback_timeout_s > 0.0)) throw std::invalid_argument("DdsLink: feedback_timeout_s must be positive");
  if (!(config.busy_wait_s >= 0.0)) throw std::invalid_argument("DdsLink: busy_wait_s must not be negative");
  newest_.step = -1;
  const DdsQos partition = site_partition_qos(config.test_id, config.site_id);
  heartbeat_subscriber_ =
      DdsEntity(dds_create_subscriber(participant.get(), partition.get(), nullptr), "dds_create_subscriber");
  heartbeat_reader_ = DdsEntity(dds_create_reader(heartbeat_subscriber_.get(), participant.heartbeat_topic(),
                                                  heartbeat_qos(config.qos).get(), nullptr),
                                "dds_create_reader(heartbeat)");
}

bool DdsLink::node_reports_matched() {
  rpsd_dds_NodeHeartbeat wire{};
  void* samples[1] = {&wire};
  dds_sample_info_t info[1];
  while (dds_take(heartbeat_reader_.get(), samples, info, 1, 1) > 0) {
    if (info[0].valid_data && wire.test_id == config_.test_id && wire.site_id == config_.site_id) {
      node_matched_ = wire.coordinator_matched;
    }
  }
  return node_matched_;
}

bool DdsLink::wait_for_node(double timeout_s) {
  const std::int64_t until = realtime::monotonic_now_ns() + static_cast<std::int64_t>(timeout_s * 1e9);
  // Both conditions at once: the node's heartbeat may say so before this side has matched.
  while (!(node_reports_matched() && ports_.peer_matched())) {
    if (realtime::monotonic_now_ns() > until) return false;
    dds_sleepfor(DDS_MSECS(10));
  }
  return true;
}

LinkStatus DdsLink::send(const CommandSample& command) {
  rpsd_dds_Command wire{};
  copy_command(command, wire);
  wire.test_id = config_.test_id;
  wire.site_id = config_.site_id;
  sent_at_ns_ = realtime::monotonic_now_ns();
  if (dds_write(ports_.writer(), &wire) < 0) return LinkStatus::kPeerLost;
  sent_step_ = command.step;
  ++counters_.sent;
  return LinkStatus::kOk;
}

namespace {

// A sample that must stop the test: the node reports a fault, or a measurement is not a
// number. In real time several samples can arrive between two receives and only the newest
// is handed on, so such a sample is held rather than passed over.
bool carries_alarm(const FeedbackSample& sample) {
  return (sample.status & kNodeFault) != 0 || has_non_finite_measurement(sample, sample.channels);
}

}  // namespace

void DdsLink::drain() {
  rpsd_dds_Feedback wire{};
  void* samples[1] = {&wire};
  dds_sample_info_t info[1];
  while (dds_take(ports_.reader(), samples, info, 1, 1) > 0) {
    if (!info[0].valid_data) continue;
    FeedbackSample sample;
    copy_feedback(wire, sample);
    if (sample.test_id != config_.test_id || sample.site_id != config_.site_id) {
      ++counters_.wrong_test_or_site;
    } else if (sample.channels != config_.channels) {
      ++counters_.wrong_channels;
    } else if (have_newest_ && sample.step < newest_.step) {
      ++counters_.older_step;
    } else if (holding_alarm_) {
      ++counters_.received;  // newer, but the alarm stays the newest until the loop has seen it
    } else {
      newest_ = sample;
      have_newest_ = true;
      newest_at_ns_ = realtime::monotonic_now_ns();
      ++counters_.received;
      holding_alarm_ = carries_alarm(sample);
    }
  }
}

LinkStatus DdsLink::receive(FeedbackSample& feedback) {
  std::int64_t deadline = sent_at_ns_ + static_cast<std::int64_t>(config_.feedback_timeout_s * 1e9);
  if (receive_deadline_ns_ > 0 && receive_deadline_ns_ < deadline) deadline = receive_deadline_ns_;
  drain();
  if (config_.busy_wait_s > 0.0 && receive_deadline_ns_ <= 0) {
    const std::int64_t until = std::min(deadline, sent_at_ns_ + static_cast<std::int64_t>(config_.busy_wait_s * 1e9));
    while (!(have_newest_ && newest_.step >= sent_step_) && realtime::monotonic_now_ns() < until) drain();
  }
  while (!(have_newest_ && newest_.step >= sent_step_)) {
    ++counters_.waits;
    if (!ports_.wait_for_data_until(deadline)) break;
    drain();
  }
  const bool on_time = have_newest_ && newest_.step >= sent_step_;
  if (have_newest_) {
    feedback = newest_;
    const std::int64_t round_trip = (on_time ? newest_at_ns_ : realtime::monotonic_now_ns()) - sent_at_ns_;
    for (int c = 0; c < config_.channels; ++c) feedback.round_trip_ns[c] = round_trip;
  }
  if (on_time) return LinkStatus::kOk;
  ++counters_.late;
  return ports_.peer_alive() ? LinkStatus::kTimeout : LinkStatus::kPeerLost;
}

}  // namespace rpsd::transport
