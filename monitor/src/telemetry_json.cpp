#include "rpsd/monitor/telemetry_json.h"

#include <cmath>

namespace rpsd::monitor {
namespace {

using nlohmann::json;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

template <typename Field>
json per_channel(const telemetry::TelemetryBatch& batch, int channels, Field field) {
  json columns = json::array();
  for (int c = 0; c < channels; ++c) {
    json column = json::array();
    for (int i = 0; i < batch.count; ++i) column.push_back(number(field(batch.samples[i])[c]));
    columns.push_back(std::move(column));
  }
  return columns;
}

}  // namespace

const char* run_state_name(telemetry::RunState state) {
  switch (state) {
    case telemetry::RunState::kStarting:
      return "starting";
    case telemetry::RunState::kRunning:
      return "running";
    case telemetry::RunState::kHeld:
      return "held";
    case telemetry::RunState::kEnded:
      return "ended";
  }
  return "unknown";
}

const char* event_kind_name(telemetry::EventKind kind) {
  switch (kind) {
    case telemetry::EventKind::kRunStarted:
      return "run_started";
    case telemetry::EventKind::kLimit:
      return "limit";
    case telemetry::EventKind::kNodeStatus:
      return "node_status";
    case telemetry::EventKind::kOperatorCommand:
      return "operator_command";
    case telemetry::EventKind::kRunEnded:
      return "run_ended";
  }
  return "unknown";
}

const char* action_name(operator_commands::OperatorAction action) {
  switch (action) {
    case operator_commands::OperatorAction::kStop:
      return "stop";
    case operator_commands::OperatorAction::kAbort:
      return "abort";
    case operator_commands::OperatorAction::kHold:
      return "hold";
    case operator_commands::OperatorAction::kResume:
      return "resume";
  }
  return "unknown";
}

std::optional<operator_commands::OperatorAction> parse_action(std::string_view text) {
  using operator_commands::OperatorAction;
  for (const OperatorAction a :
       {OperatorAction::kStop, OperatorAction::kAbort, OperatorAction::kHold, OperatorAction::kResume}) {
    if (text == action_name(a)) return a;
  }
  return std::nullopt;
}

json status_json(const telemetry::TelemetryStatus& s) {
  return json{{"test_id", s.test_id},
              {"run_id", s.run_id},
              {"test_name", fixed_text(s.test_name)},
              {"state", run_state_name(s.state)},
              {"steps_done", s.steps_done},
              {"steps_planned", s.steps_planned},
              {"control_rate_hz", number(s.control_rate_hz)},
              {"real_time", s.real_time},
              {"channels", s.channels},
              {"overruns", s.overruns},
              {"late_feedback", s.late_feedback},
              {"worst_feedback_age_periods", s.worst_feedback_age_periods},
              {"dropped_samples", s.dropped_samples},
              {"predicted_effective_damping", number(s.predicted_effective_damping)},
              {"identified_effective_damping", number(s.identified_effective_damping)},
              {"stopped_by", fixed_text(s.stopped_by)}};
}

json batch_json(const telemetry::TelemetryBatch& batch) {
  const int count = std::min<int>(batch.count, telemetry::kSamplesPerBatch);
  telemetry::TelemetryBatch b = batch;
  b.count = static_cast<std::uint8_t>(count);
  int channels = 0;
  for (int i = 0; i < count; ++i) channels = std::max<int>(channels, b.samples[i].channels);
  if (count == 0) channels = batch.status.channels;  // a batch of status only
  channels = std::min(channels, transport::kMaxChannels);
  json step = json::array(), time = json::array(), age = json::array(), lateness = json::array(),
       node_status = json::array(), limit_flags = json::array();
  for (int i = 0; i < count; ++i) {
    const telemetry::TelemetrySample& s = b.samples[i];
    step.push_back(s.step);
    time.push_back(number(s.time_s));
    age.push_back(s.feedback_age_periods);
    lateness.push_back(number(s.cycle_lateness_s));
    node_status.push_back(s.node_status);
    limit_flags.push_back(s.limit_flags);
  }
  using S = telemetry::TelemetrySample;
  json samples{{"channels", channels},
               {"step", std::move(step)},
               {"time_s", std::move(time)},
               {"target_m", per_channel(b, channels, [](const S& s) { return s.target_m; })},
               {"command_m", per_channel(b, channels, [](const S& s) { return s.command_m; })},
               {"measured_m", per_channel(b, channels, [](const S& s) { return s.measured_m; })},
               {"measured_force_n", per_channel(b, channels, [](const S& s) { return s.measured_force_n; })},
               {"round_trip_s", per_channel(b, channels, [](const S& s) { return s.round_trip_s; })},
               {"feedback_age_periods", std::move(age)},
               {"cycle_lateness_s", std::move(lateness)},
               {"node_status", std::move(node_status)},
               {"limit_flags", std::move(limit_flags)}};
  return json{{"type", "batch"},
              {"sequence", batch.sequence},
              {"run_id", batch.status.run_id},
              {"status", status_json(batch.status)},
              {"samples", std::move(samples)}};
}

json event_json(const telemetry::TelemetryEvent& e) {
  return json{{"type", "event"},
              {"test_id", e.test_id},
              {"run_id", e.run_id},
              {"kind", event_kind_name(e.kind)},
              {"step", e.step},
              {"time_s", number(e.time_s)},
              {"wall_clock_unix_ns", e.wall_clock_unix_ns},
              {"text", fixed_text(e.text)}};
}

json reply_json(const operator_commands::OperatorReply& r) {
  return json{{"test_id", r.test_id},
              {"run_id", r.run_id},
              {"sequence", r.sequence},
              {"status", r.status == operator_commands::ReplyStatus::kDone ? "done" : "refused"},
              {"text", fixed_text(r.text)}};
}

}  // namespace rpsd::monitor
