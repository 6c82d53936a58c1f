#include "rpsd/transport/dds_link.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
  if (config_.run_id == 0) config_.run_id = draw_run_id();
  newest_.step = -1;
  const DdsQos partition = site_partition_qos(config.test_id, config.site_id);
  heartbeat_subscriber_ =
      DdsEntity(dds_create_subscriber(participant.get(), partition.get(), nullptr), "dds_create_subscriber");
  heartbeat_reader_ = DdsEntity(dds_create_reader(heartbeat_subscriber_.get(), participant.heartbeat_topic(),
                                                  heartbeat_qos(config.qos).get(), nullptr),
                                "dds_create_reader(heartbeat)");
}

namespace {

// One control rate, to a rounding error: 1/f on one side and dt/iterations on the other.
bool same_period(double a, double b) {
  return a > 0.0 && b > 0.0 && std::isfinite(a) && std::isfinite(b) && std::abs(a - b) <= 1e-6 * std::max(a, b);
}

}  // namespace

void DdsLink::refuse(NodeRefusal::Kind kind, std::uint64_t serving_run_id, double node_period_s) {
  if (refusal_.kind != NodeRefusal::Kind::kNone) return;  // the first reason stands
  refusal_ = {kind, serving_run_id, node_period_s};
}

bool DdsLink::node_reports_matched() {
  rpsd_dds_NodeHeartbeat wire{}, newest{};
  void* samples[1] = {&wire};
  dds_sample_info_t info[1];
  bool heard = false;
  while (dds_take(heartbeat_reader_.get(), samples, info, 1, 1) > 0) {
    if (info[0].valid_data && wire.test_id == config_.test_id && wire.site_id == config_.site_id) {
      newest = wire;
      heard = true;
    }
  }
  // Only the newest counts: an older heartbeat may name a run the node has since ended.
  if (heard) {
    node_matched_ = newest.coordinator_matched;
    NodeHeartbeat said;
    copy_heartbeat(newest, said);
    node_heartbeat_ = said;
    if (newest.state == NodeHeartbeat::kFaulted && newest.fault_text[0] != '\0') {
      std::ranges::copy(newest.fault_text, node_fault_text_.begin());
      node_fault_text_.back() = '\0';
    }
    if (!same_period(newest.control_period_s, config_.qos.control_period_s)) {
      refuse(NodeRefusal::Kind::kRateMismatch, 0, newest.control_period_s);
    } else if (newest.serving_run_id != 0 && newest.serving_run_id != config_.run_id) {
      refuse(NodeRefusal::Kind::kServingOtherRun, newest.serving_run_id, 0.0);
    }
  }
  return node_matched_;
}

bool DdsLink::wait_for_node(double timeout_s) {
  const std::int64_t until = realtime::monotonic_now_ns() + static_cast<std::int64_t>(timeout_s * 1e9);
  // Both conditions at once: the node's heartbeat may say so before this side has matched.
  while (!(node_reports_matched() && ports_.peer_matched())) {
    if (refusal_.kind != NodeRefusal::Kind::kNone) return false;
    if (realtime::monotonic_now_ns() > until) return false;
    dds_sleepfor(DDS_MSECS(10));
  }
  return refusal_.kind == NodeRefusal::Kind::kNone;
}

std::string DdsLink::node_fault_text(double wait_s) {
  const std::int64_t until = realtime::monotonic_now_ns() + static_cast<std::int64_t>(wait_s * 1e9);
  for (;;) {
    node_reports_matched();
    if (node_fault_text_[0] != '\0' || realtime::monotonic_now_ns() > until) break;
    dds_sleepfor(DDS_MSECS(10));
  }
  return std::string(node_fault_text_.data());
}

std::string DdsLink::refusal_text() const {
  char text[320];
  const unsigned site = config_.site_id;
  switch (refusal_.kind) {
    case NodeRefusal::Kind::kNone:
      return {};
    case NodeRefusal::Kind::kServingOtherRun:
      std::snprintf(text, sizeof text,
                    "site %u is serving another run (run %s; this run is %s): a node serves one run at a time", site,
                    run_id_text(refusal_.serving_run_id).c_str(), run_id_text(config_.run_id).c_str());
      return text;
    case NodeRefusal::Kind::kRateMismatch: {
      const double node = refusal_.node_control_period_s, own = config_.qos.control_period_s;
      if (!(node > 0.0)) {
        std::snprintf(text, sizeof text, "site %u states no control rate, and this test runs at %g Hz", site,
                      1.0 / own);
      } else {
        std::snprintf(text, sizeof text,
                      "site %u runs at %g Hz and this test at %g Hz (control periods %g s and %g s): node and "
                      "coordinator must run at one rate",
                      site, 1.0 / node, 1.0 / own, node, own);
      }
      return text;
    }
  }
  return {};
}

void DdsLink::end_run() {
  if (counters_.sent == 0) return;  // a run refused at the start never reached the node
  rpsd_dds_Command wire{};
  wire.test_id = config_.test_id;
  wire.site_id = config_.site_id;
  wire.run_id = config_.run_id;
  wire.step = sent_step_ + 1;
  wire.control_period_s = config_.qos.control_period_s;
  wire.channels = static_cast<std::uint8_t>(config_.channels);
  wire.end_of_run = true;
  // Best effort may lose one; a node takes the repeats as the same end.
  const int copies = config_.qos.newest_only ? 3 : 1;
  for (int i = 0; i < copies; ++i) dds_write(ports_.writer(), &wire);
}

void DdsLink::keep_alive() {
  if (counters_.sent == 0) return;
  rpsd_dds_Command wire{};
  copy_command(last_command_, wire);
  wire.test_id = config_.test_id;
  wire.site_id = config_.site_id;
  wire.run_id = config_.run_id;
  wire.control_period_s = config_.qos.control_period_s;
  wire.end_of_run = false;
  dds_write(ports_.writer(), &wire);
}

LinkStatus DdsLink::send(const CommandSample& command) {
  last_command_ = command;
  rpsd_dds_Command wire{};
  copy_command(command, wire);
  wire.test_id = config_.test_id;
  wire.site_id = config_.site_id;
  wire.run_id = config_.run_id;
  wire.control_period_s = config_.qos.control_period_s;
  wire.end_of_run = false;
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
    const std::uint64_t writer = info[0].publication_handle;
    if (sample.test_id != config_.test_id || sample.site_id != config_.site_id) {
      ++counters_.wrong_test_or_site;
    } else if (sample.run_id == 0) {
      ++counters_.no_run;
    } else if (node_writer_ != 0 && writer != node_writer_) {
      ++counters_.unknown_writer;  // not the node that has been answering this run
    } else if (sample.run_id != config_.run_id) {
      // The node of this site (the one answering this run, or before any answer any writer
      // here) serves another run: this run cannot have the site.
      ++counters_.other_run;
      refuse(NodeRefusal::Kind::kServingOtherRun, sample.run_id, 0.0);
    } else if (sample.step > sent_step_) {  // of this run: another run's steps are its own
      // Taken, it would make every true answer after it look older (as a forged command with
      // step 9e18 once did to a node).
      ++counters_.impossible_step;
    } else if (sample.channels != config_.channels) {
      ++counters_.wrong_channels;
    } else if (have_newest_ && sample.step < newest_.step) {
      ++counters_.older_step;
    } else if (holding_alarm_) {
      ++counters_.received;  // newer, but the alarm stays the newest until the loop has seen it
    } else {
      node_writer_ = writer;
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
  const auto refused = [this] { return refusal_.kind != NodeRefusal::Kind::kNone; };
  const auto answered = [this] { return have_newest_ && newest_.step >= sent_step_; };
  drain();
  if (config_.busy_wait_s > 0.0 && receive_deadline_ns_ <= 0) {
    const std::int64_t until = std::min(deadline, sent_at_ns_ + static_cast<std::int64_t>(config_.busy_wait_s * 1e9));
    while (!answered() && !refused() && realtime::monotonic_now_ns() < until) drain();
  }
  while (!answered() && !refused()) {
    ++counters_.waits;
    if (!ports_.wait_for_data_until(deadline)) break;
    drain();
  }
  // No answer: the node's heartbeat may say why (it serves another run that sends nothing now).
  if (!answered() && !refused()) node_reports_matched();
  if (refused()) return LinkStatus::kRefused;
  const bool on_time = answered();
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
