#include "telemetry_topics.h"

#include <cmath>

namespace rpsd::telemetry {

std::string telemetry_partition_name(std::uint32_t test_id) {
  return "rpsd/test-" + std::to_string(test_id) + "/telemetry";
}

TelemetryParticipant::TelemetryParticipant(std::uint32_t domain_id, const std::string& dds_config)
    : participant_(transport::DdsDomainConfig{domain_id, dds_config}) {
  batch_topic_ = transport::DdsEntity(
      dds_create_topic(participant_.get(), &rpsd_telemetry_Batch_desc, "rpsd_TelemetryBatch", nullptr, nullptr),
      "dds_create_topic(rpsd_TelemetryBatch)");
  event_topic_ = transport::DdsEntity(
      dds_create_topic(participant_.get(), &rpsd_telemetry_Event_desc, "rpsd_TelemetryEvent", nullptr, nullptr),
      "dds_create_topic(rpsd_TelemetryEvent)");
}

transport::DdsQos telemetry_partition_qos(std::uint32_t test_id) {
  transport::DdsQos q;
  dds_qset_partition1(q.get(), telemetry_partition_name(test_id).c_str());
  return q;
}

transport::DdsQos telemetry_qos(int depth) {
  transport::DdsQos q;
  // Reliable with a keep-last history: Cyclone never throttles a keep-last writer (its
  // watermarks apply to keep-all only), so a slow or vanished reader cannot make a write wait;
  // max_blocking_time 0 makes any wait a refusal the publisher counts instead.
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, 0);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, depth);
  dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  // What a late joiner gets: Cyclone keeps a transient-local writer's past by the durability
  // service's history (default: the last sample only), not by the writer's own.
  dds_qset_durability_service(q.get(), 0, DDS_HISTORY_KEEP_LAST, depth, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED);
  dds_qset_liveliness(q.get(), DDS_LIVELINESS_AUTOMATIC,
                      static_cast<dds_duration_t>(std::llround(kLivelinessLeaseS * 1e9)));
  return q;
}

namespace {

template <class In, class Out>
void copy_sample(const In& in, Out& out) {
  out.step = in.step;
  out.time_s = in.time_s;
  out.channels = in.channels;
  std::ranges::copy(in.target_m, std::begin(out.target_m));
  std::ranges::copy(in.command_m, std::begin(out.command_m));
  std::ranges::copy(in.measured_m, std::begin(out.measured_m));
  std::ranges::copy(in.measured_force_n, std::begin(out.measured_force_n));
  std::ranges::copy(in.round_trip_s, std::begin(out.round_trip_s));
  out.feedback_age_periods = in.feedback_age_periods;
  out.cycle_lateness_s = in.cycle_lateness_s;
  out.node_status = in.node_status;
  out.limit_flags = in.limit_flags;
}

template <class In, class Out>
void copy_status(const In& in, Out& out) {
  out.test_id = in.test_id;
  out.run_id = in.run_id;
  std::ranges::copy(in.test_name, std::begin(out.test_name));
  out.steps_done = in.steps_done;
  out.steps_planned = in.steps_planned;
  out.control_rate_hz = in.control_rate_hz;
  out.real_time = in.real_time;
  out.channels = in.channels;
  out.overruns = in.overruns;
  out.late_feedback = in.late_feedback;
  out.worst_feedback_age_periods = in.worst_feedback_age_periods;
  out.dropped_samples = in.dropped_samples;
  out.predicted_effective_damping = in.predicted_effective_damping;
  out.identified_effective_damping = in.identified_effective_damping;
  std::ranges::copy(in.stopped_by, std::begin(out.stopped_by));
}

template <class In, class Out>
void copy_event(const In& in, Out& out) {
  out.test_id = in.test_id;
  out.run_id = in.run_id;
  out.step = in.step;
  out.time_s = in.time_s;
  out.wall_clock_unix_ns = in.wall_clock_unix_ns;
  std::ranges::copy(in.text, std::begin(out.text));
}

// A text from the wire always ends within its array.
template <class Array>
void terminate(Array& text) {
  text.back() = '\0';
}

}  // namespace

void to_wire(const TelemetryBatch& in, rpsd_telemetry_Batch& out) {
  out.batch_sequence = in.sequence;
  copy_status(in.status, out.status);
  out.status.state = static_cast<std::uint8_t>(in.status.state);
  out.count = in.count;
  for (int i = 0; i < kSamplesPerBatch; ++i) copy_sample(in.samples[i], out.samples[i]);
}

void from_wire(const rpsd_telemetry_Batch& in, TelemetryBatch& out) {
  out.sequence = in.batch_sequence;
  copy_status(in.status, out.status);
  out.status.state = static_cast<RunState>(std::min<std::uint8_t>(in.status.state, 3));
  terminate(out.status.test_name);
  terminate(out.status.stopped_by);
  out.count = std::min<std::uint8_t>(in.count, kSamplesPerBatch);
  for (int i = 0; i < kSamplesPerBatch; ++i) {
    copy_sample(in.samples[i], out.samples[i]);
    out.samples[i].channels = std::min<std::uint8_t>(out.samples[i].channels, transport::kMaxChannels);
  }
  out.status.channels = std::min<std::uint8_t>(out.status.channels, transport::kMaxChannels);
}

void to_wire(const TelemetryEvent& in, rpsd_telemetry_Event& out) {
  copy_event(in, out);
  out.kind = static_cast<std::uint8_t>(in.kind);
}

void from_wire(const rpsd_telemetry_Event& in, TelemetryEvent& out) {
  copy_event(in, out);
  out.kind = static_cast<EventKind>(std::min<std::uint8_t>(in.kind, 4));
  terminate(out.text);
}

}  // namespace rpsd::telemetry
