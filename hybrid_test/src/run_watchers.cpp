#include "rpsd/hybrid_test/run_watchers.h"

#include <algorithm>
#include <cstdio>

#include "rpsd/operator_commands/operator_command_sender.h"

namespace rpsd::hybrid_test {

RealTimeProgress::RealTimeProgress(ProgressSink sink, std::size_t case_number, std::size_t cases)
    : sink_(std::move(sink)), case_number_(case_number), cases_(cases) {}

void RealTimeProgress::start(std::int64_t steps_planned, bool real_time, const coordinator::LiveCounters* live) {
  planned_ = steps_planned;
  real_time_ = real_time;
  live_ = live;
  worst_age_ = 0;
  last_report_ = Clock::now();
}

void RealTimeProgress::observe(const coordinator::StepRecord& r) {
  if (!real_time_ || !sink_) return;
  worst_age_ = std::max(worst_age_, static_cast<int>(r.feedback_age_periods));
  // The clock is read every 64 records only: at 1024 Hz and more that is still ~16 a second.
  if (r.step % 64 != 0) return;
  const Clock::time_point now = Clock::now();
  if (now - last_report_ < kEvery) return;
  last_report_ = now;
  ProgressReport report{"test", case_number_, cases_, r.step, planned_};  // steps count from 1
  report.real_time = true;
  report.overruns = live_ ? live_->overruns.load(std::memory_order_relaxed) : 0;
  report.worst_feedback_age_periods = worst_age_;
  sink_(report);
}

namespace {

std::unique_ptr<telemetry::TelemetryPublisher> make_publisher(const TestConfig& test) {
  if (!test.telemetry.enabled) return nullptr;
  telemetry::TelemetryPublisherConfig c;
  c.domain_id = test.transport.domain_id;
  c.dds_config = test.transport.dds_config.string();
  c.test_id = test.transport.test_id;
  c.test_name = test.name;
  c.max_samples_per_s = test.telemetry.max_samples_per_s;
  return std::make_unique<telemetry::TelemetryPublisher>(c);
}

}  // namespace

RunWatchers::RunWatchers(const TestConfig& test, const ProgressSink& progress, std::size_t case_number,
                         std::size_t cases)
    : test_(test), progress_(progress, case_number, cases), telemetry_(make_publisher(test)) {}

RunWatchers::~RunWatchers() {
  if (!telemetry_ || !started_ || ended_) return;
  try {
    telemetry_->end({"the run did not finish"});
  } catch (...) {
    // Nothing more to tell a monitor: its publisher goes and its liveliness with it.
  }
}

RunWatch RunWatchers::watch() {
  RunWatch w;
  w.observers.push_back(&progress_);
  if (telemetry_) w.observers.push_back(telemetry_.get());
  w.started = [this](const TestAssembly& run) {
    progress_.start(run.steps_planned(), run.real_time(), &run.live_counters());
    if (telemetry_) {
      telemetry::TelemetryRunInfo info;
      info.run_id = run.run_id();
      info.steps_planned = run.steps_planned();
      info.control_rate_hz = test_.control_rate_hz;
      info.real_time = run.real_time();
      info.channels = static_cast<int>(test_.experimental.size());
      info.live = &run.live_counters();
      info.predicted_effective_damping = test_.telemetry.predicted_effective_damping;
      info.lowest_mode = test_.telemetry.lowest_mode;
      telemetry_->start(info);
    }
    started_ = true;
  };
  // Each operator command the run heard, as an event on the page; a hold or resume done
  // changes the run's state there. On the listener's thread.
  if (telemetry_) {
    w.on_operator_command = [this](const operator_commands::OperatorCommandEvent& heard) {
      telemetry::TelemetryEvent event;
      event.kind = telemetry::EventKind::kOperatorCommand;
      event.wall_clock_unix_ns = heard.received_unix_ns;
      std::snprintf(event.text.data(), event.text.size(), "%s from %s: %s",
                    operator_commands::operator_action_name(heard.action), heard.sender.c_str(), heard.reply.c_str());
      telemetry_->publish_event(event);
      if (heard.status == operator_commands::ReplyStatus::kDone) {
        if (heard.action == operator_commands::OperatorAction::kHold) telemetry_->set_held(true);
        if (heard.action == operator_commands::OperatorAction::kResume) telemetry_->set_held(false);
      }
    };
  }
  return w;
}

void RunWatchers::ended(const TestRun& test, std::string_view outcome) {
  ended_ = true;
  if (!telemetry_ || !started_) return;
  telemetry::TelemetryRunEnd end;
  end.stopped_by = outcome;
  end.stopped_by_limit = test.outcome == coordinator::StepOutcome::kLimit ||
                         test.outcome == coordinator::StepOutcome::kRunAway ||
                         test.outcome == coordinator::StepOutcome::kGeometry;
  end.overruns = test.timing.overruns;
  end.late_feedback = test.timing.late_feedback;
  telemetry_->end(end);
}

}  // namespace rpsd::hybrid_test
