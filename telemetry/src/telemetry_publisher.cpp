#include "rpsd/telemetry/telemetry_publisher.h"

#include <chrono>
#include <cmath>
#include <string>

#include "telemetry_topics.h"

namespace rpsd::telemetry {

namespace {

using Clock = std::chrono::steady_clock;
// A partial batch waits at most this long on an idle writer (a slow real-time run fills one
// in 125 ms at 256 samples/s; a monitor at 25 frames/s wants no older data than that).
constexpr auto kPartialBatchWait = std::chrono::milliseconds(100);

std::int64_t unix_ns_now() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string flag_names(std::uint32_t flags, const std::pair<std::uint32_t, const char*>* names, std::size_t n) {
  std::string text;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(flags & names[i].first)) continue;
    if (!text.empty()) text += ", ";
    text += names[i].second;
  }
  return text.empty() ? "none" : text;
}

std::string limit_text(std::uint32_t flags) {
  static constexpr std::pair<std::uint32_t, const char*> kNames[] = {{transport::kLimitStroke, "stroke"},
                                                                     {transport::kLimitVelocity, "velocity"},
                                                                     {transport::kLimitForce, "force"},
                                                                     {transport::kLimitIncrement, "increment"},
                                                                     {transport::kLimitAcceleration, "acceleration"}};
  return "node limits acting: " + flag_names(flags, kNames, std::size(kNames));
}

std::string node_status_text(std::uint32_t status) {
  static constexpr std::pair<std::uint32_t, const char*> kNames[] = {
      {transport::kNodeLimitActive, "limit active"},
      {transport::kNodeFault, "fault"},
      {transport::kNodeHolding, "holding"},
      {transport::kNodeEndStop, "end stop"},
      {transport::kNodeValveSaturated, "valve saturated"}};
  return status == transport::kNodeOk ? "nodes ok" : "nodes: " + flag_names(status, kNames, std::size(kNames));
}

}  // namespace

struct TelemetryPublisher::Parts {
  explicit Parts(const TelemetryPublisherConfig& c)
      : config(c),
        participant(c.domain_id, c.dds_config),
        publisher(dds_create_publisher(participant.get(), telemetry_partition_qos(c.test_id).get(), nullptr),
                  "dds_create_publisher(telemetry)"),
        batch_writer(
            dds_create_writer(publisher.get(), participant.batch_topic(), telemetry_qos(kBatchHistory).get(), nullptr),
            "dds_create_writer(rpsd_TelemetryBatch)"),
        event_writer(
            dds_create_writer(publisher.get(), participant.event_topic(), telemetry_qos(kEventHistory).get(), nullptr),
            "dds_create_writer(rpsd_TelemetryEvent)") {
    batch.status.test_id = c.test_id;
    set_text(batch.status.test_name, c.test_name);
  }

  TelemetryPublisherConfig config;
  TelemetryParticipant participant;
  transport::DdsEntity publisher, batch_writer, event_writer;
  TelemetryRunInfo run;
  std::int64_t keep_every = 1;
  EffectiveDampingIdentifier damping;  // fed every step, read at each batch
  TelemetryBatch batch;                // the one being filled; its status is the run's
  rpsd_telemetry_Batch wire{};         // written from here: ~12 kB, kept off the stack
  bool have_previous = false;
  std::uint32_t previous_limit_flags = 0, previous_node_status = 0;
  std::int64_t last_step = -1;
  double last_time_s = 0.0;
  Clock::time_point batch_started;  // when the first change not yet sent came
  std::int64_t steps_sent = 0;      // the status's steps_done as last written
  std::uint64_t sent = 0;

  void write_batch() {
    TelemetryStatus& s = batch.status;
    if (run.live) {
      s.overruns = run.live->overruns.load(std::memory_order_relaxed);
      s.late_feedback = run.live->late_feedback.load(std::memory_order_relaxed);
    }
    s.identified_effective_damping = damping.damping_ratio();
    to_wire(batch, wire);
    if (dds_write(batch_writer.get(), &wire) < 0) {
      s.dropped_samples += batch.count;
    } else {
      ++sent;
    }
    ++batch.sequence;
    batch.count = 0;
    steps_sent = s.steps_done;
  }

  void write_event(TelemetryEvent e) {
    if (e.test_id == 0) e.test_id = config.test_id;
    if (e.run_id == 0) e.run_id = run.run_id;
    if (e.wall_clock_unix_ns == 0) e.wall_clock_unix_ns = unix_ns_now();
    rpsd_telemetry_Event w{};
    to_wire(e, w);
    dds_write(event_writer.get(), &w);  // a refusal loses the event only: nothing waits
  }

  void event(EventKind kind, std::string_view text) {
    TelemetryEvent e;
    e.kind = kind;
    e.step = last_step;
    e.time_s = last_time_s;
    set_text(e.text, text);
    write_event(e);
  }
};

TelemetryPublisher::TelemetryPublisher(const TelemetryPublisherConfig& config)
    : parts_(std::make_unique<Parts>(config)) {}

TelemetryPublisher::~TelemetryPublisher() = default;

void TelemetryPublisher::start(const TelemetryRunInfo& run) {
  const std::lock_guard lock(mutex_);
  Parts& p = *parts_;
  p.run = run;
  const double max_rate = p.config.max_samples_per_s > 0.0 ? p.config.max_samples_per_s : run.control_rate_hz;
  p.keep_every = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(run.control_rate_hz / max_rate - 1e-9)));
  TelemetryStatus& s = p.batch.status;
  s.run_id = run.run_id;
  s.state = RunState::kRunning;
  s.steps_planned = run.steps_planned;
  s.control_rate_hz = run.control_rate_hz;
  s.real_time = run.real_time;
  s.channels = static_cast<std::uint8_t>(run.channels);
  s.predicted_effective_damping = run.predicted_effective_damping;
  p.damping.configure(run.lowest_mode, run.control_rate_hz);
  p.batch.sequence = 0;
  p.batch.count = 0;
  p.event(EventKind::kRunStarted, std::string("run started: ") + p.config.test_name + ", " +
                                      std::to_string(run.steps_planned) + " steps at " +
                                      std::to_string(static_cast<long long>(std::llround(run.control_rate_hz))) +
                                      " Hz" + (run.real_time ? ", real time" : ", as fast as possible"));
}

void TelemetryPublisher::observe(const coordinator::StepRecord& r) {
  const std::lock_guard lock(mutex_);
  Parts& p = *parts_;
  p.last_step = r.step;
  p.last_time_s = r.time_s;
  TelemetryStatus& s = p.batch.status;
  if (p.batch.count == 0 && s.steps_done == p.steps_sent) p.batch_started = Clock::now();
  s.steps_done = r.step;  // steps count from 1
  s.worst_feedback_age_periods = std::max(s.worst_feedback_age_periods, r.feedback_age_periods);
  // Events are never decimated: every change of the nodes' limits and states.
  if (!p.have_previous || r.limit_flags != p.previous_limit_flags) {
    if (p.have_previous || r.limit_flags != 0) p.event(EventKind::kLimit, limit_text(r.limit_flags));
    p.previous_limit_flags = r.limit_flags;
  }
  if (!p.have_previous || r.node_status != p.previous_node_status) {
    if (p.have_previous || r.node_status != 0) p.event(EventKind::kNodeStatus, node_status_text(r.node_status));
    p.previous_node_status = r.node_status;
  }
  p.have_previous = true;
  p.damping.observe(r);
  if (r.step % p.keep_every != 0) return;
  TelemetrySample& t = p.batch.samples[p.batch.count++];
  t.step = r.step;
  t.time_s = r.time_s;
  t.channels = r.channels;
  for (int c = 0; c < r.channels; ++c) {
    t.target_m[c] = r.target_m[c];
    t.command_m[c] = r.command_m[c];
    t.measured_m[c] = r.measured_m[c];
    t.measured_force_n[c] = r.measured_force_n[c];
    t.round_trip_s[c] = r.round_trip_s[c];
  }
  t.feedback_age_periods = r.feedback_age_periods;
  t.cycle_lateness_s = r.cycle_lateness_s;
  t.node_status = r.node_status;
  t.limit_flags = r.limit_flags;
  if (p.batch.count == kSamplesPerBatch) p.write_batch();
}

void TelemetryPublisher::idle() {
  const std::lock_guard lock(mutex_);
  Parts& p = *parts_;
  // Steps taken but not kept (decimated) count too: a held run's last step shows on the page.
  const bool unsent = p.batch.count > 0 || p.batch.status.steps_done != p.steps_sent;
  if (unsent && Clock::now() - p.batch_started >= kPartialBatchWait) p.write_batch();
}

void TelemetryPublisher::publish_event(const TelemetryEvent& event) {
  const std::lock_guard lock(mutex_);
  TelemetryEvent e = event;
  // An event from outside the records (an operator's command) happened at the last step
  // recorded (-1: before the first).
  if (e.step == 0 && e.time_s == 0.0) {
    e.step = parts_->last_step;
    e.time_s = parts_->last_time_s;
  }
  parts_->write_event(e);
}

void TelemetryPublisher::set_held(bool held) {
  const std::lock_guard lock(mutex_);
  Parts& p = *parts_;
  if (p.batch.status.state == RunState::kEnded) return;
  p.batch.status.state = held ? RunState::kHeld : RunState::kRunning;
  p.write_batch();  // the state shows now, with whatever samples wait
}

void TelemetryPublisher::end(const TelemetryRunEnd& end) {
  const std::lock_guard lock(mutex_);
  Parts& p = *parts_;
  p.run.live = nullptr;
  p.batch.status.overruns = end.overruns;
  p.batch.status.late_feedback = end.late_feedback;
  if (end.stopped_by_limit) p.event(EventKind::kLimit, end.stopped_by);
  p.batch.status.state = RunState::kEnded;
  set_text(p.batch.status.stopped_by, end.stopped_by);
  p.write_batch();
  p.event(EventKind::kRunEnded, "run ended: " + end.stopped_by);
}

std::int64_t TelemetryPublisher::keep_every_steps() const {
  const std::lock_guard lock(mutex_);
  return parts_->keep_every;
}

std::uint64_t TelemetryPublisher::batches_sent() const {
  const std::lock_guard lock(mutex_);
  return parts_->sent;
}

std::int64_t TelemetryPublisher::dropped_samples() const {
  const std::lock_guard lock(mutex_);
  return parts_->batch.status.dropped_samples;
}

}  // namespace rpsd::telemetry
