// The telemetry over DDS on loopback: what a subscriber gets is every k-th step as recorded,
// in batches without gaps, with the run's status and events; one that joins mid-run gets the
// recent past; one that never reads, or goes away, changes nothing in the run.
#include "rpsd/telemetry/telemetry_publisher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/specimen_sdof.h"
#include "telemetry_test_domain.h"

namespace rpsd::telemetry {
namespace {

using hybrid_test::TestAssembly;
using testing::loopback_xml;
using testing::test_domain;

hybrid_test::TestConfig sdof(double duration_s) {
  hybrid_test::SpecimenSdof s;
  s.duration_s = duration_s;
  return hybrid_test::specimen_sdof_test(s);
}

TelemetryPublisherConfig publisher_config(std::uint32_t test_id, double samples_per_s = 256.0) {
  return {test_domain(), loopback_xml(), test_id, "telemetry test", samples_per_s};
}

TelemetryRunInfo run_info(const TestAssembly& test, const hybrid_test::TestConfig& config) {
  TelemetryRunInfo info;
  info.run_id = test.run_id();
  info.steps_planned = test.steps_planned();
  info.control_rate_hz = config.control_rate_hz;
  info.channels = 1;
  info.live = &test.live_counters();
  return info;
}

// A whole run with `observers` on its recorder, keeping its records; the publisher (if any)
// started before the first step and ended after the recorder finished.
hybrid_test::TestRun run_with(const hybrid_test::TestConfig& config, TelemetryPublisher* publisher,
                              std::vector<coordinator::RecordObserver*> observers = {}) {
  if (publisher) observers.push_back(publisher);
  TestAssembly test(config, {{}, false, true, {}, nullptr, observers});
  if (publisher) publisher->start(run_info(test, config));
  const coordinator::StepOutcome outcome = test.run({}, {});
  hybrid_test::TestRun run = test.finish(outcome);
  if (publisher) publisher->end({"completed", false, run.timing.overruns, run.timing.late_feedback});
  return run;
}

TEST(TelemetryPublisher, ASubscriberGetsEveryKthStepAsRecordedInBatchesWithoutGaps) {
  const hybrid_test::TestConfig config = sdof(2.0);  // 2048 steps at 1024 Hz
  TelemetrySubscriber subscriber({test_domain(), loopback_xml(), 11});
  TelemetryPublisher publisher(publisher_config(11));
  ASSERT_TRUE(testing::wait_for_publisher(subscriber));
  const hybrid_test::TestRun run = run_with(config, &publisher);
  ASSERT_EQ(run.steps, 2048);
  EXPECT_EQ(publisher.keep_every_steps(), 4);  // 1024 Hz to at most 256 samples/s
  const testing::Received got = testing::collect_until_ended(subscriber);
  ASSERT_TRUE(got.ended());

  std::vector<TelemetrySample> samples;
  for (std::size_t b = 0; b < got.batches.size(); ++b) {
    EXPECT_EQ(got.batches[b].sequence, b) << "a batch lost";
    EXPECT_EQ(got.batches[b].status.run_id, run.run_id);
    for (int i = 0; i < got.batches[b].count; ++i) samples.push_back(got.batches[b].samples[i]);
  }
  std::vector<const coordinator::StepRecord*> kept;
  for (const auto& r : run.records)
    if (r.step % 4 == 0) kept.push_back(&r);
  ASSERT_EQ(samples.size(), kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const coordinator::StepRecord& r = *kept[i];
    ASSERT_EQ(samples[i].step, r.step);
    EXPECT_EQ(samples[i].time_s, r.time_s);
    EXPECT_EQ(samples[i].channels, 1);
    EXPECT_EQ(samples[i].target_m[0], r.target_m[0]);
    EXPECT_EQ(samples[i].command_m[0], r.command_m[0]);
    EXPECT_EQ(samples[i].measured_m[0], r.measured_m[0]);
    EXPECT_EQ(samples[i].measured_force_n[0], r.measured_force_n[0]);
    EXPECT_EQ(samples[i].limit_flags, r.limit_flags);
  }
  const TelemetryStatus& last = got.batches.back().status;
  EXPECT_EQ(last.state, RunState::kEnded);
  EXPECT_STREQ(last.stopped_by.data(), "completed");
  EXPECT_EQ(last.steps_done, run.steps);
  EXPECT_EQ(last.steps_planned, 2048);
  EXPECT_EQ(last.dropped_samples, 0);
  EXPECT_STREQ(last.test_name.data(), "telemetry test");
  ASSERT_GE(got.events.size(), 2u);
  EXPECT_EQ(got.events.front().kind, EventKind::kRunStarted);
  EXPECT_EQ(got.events.back().kind, EventKind::kRunEnded);
  EXPECT_EQ(got.events.back().run_id, run.run_id);
}

// The status carries the damping identified from every step (not only the kept ones), none
// before two periods of the mode, and the prediction it was given.
TEST(TelemetryPublisher, TheStatusCarriesTheDampingIdentifiedFromEveryStep) {
  const hybrid_test::TestConfig config = sdof(3.0);
  const hybrid_test::SpecimenSdof s;
  LowestMode mode;  // the SDOF's, mass-normalised
  mode.frequency_hz = std::sqrt(s.stiffness_n_per_m / s.mass_kg) / (2.0 * M_PI);
  mode.numerical_stiffness_n_per_m = 0.0;
  mode.numerical_damping_n_s_per_m = 2.0 * s.damping_ratio * std::sqrt(s.stiffness_n_per_m / s.mass_kg);
  mode.channel_weight = {1.0 / s.mass_kg};
  TelemetrySubscriber subscriber({test_domain(), loopback_xml(), 16});
  TelemetryPublisher publisher(publisher_config(16));
  ASSERT_TRUE(testing::wait_for_publisher(subscriber));
  TestAssembly test(config, {{}, false, true, {}, nullptr, {&publisher}});
  TelemetryRunInfo info = run_info(test, config);
  info.predicted_effective_damping = 0.0123;
  info.lowest_mode = mode;
  publisher.start(info);
  const coordinator::StepOutcome outcome = test.run({}, {});
  const hybrid_test::TestRun run = test.finish(outcome);
  publisher.end({"completed", false, 0, 0});
  const testing::Received got = testing::collect_until_ended(subscriber);
  ASSERT_TRUE(got.ended());

  EffectiveDampingIdentifier direct;
  direct.configure(mode, config.control_rate_hz);
  for (const auto& r : run.records) direct.observe(r);
  const TelemetryStatus& last = got.batches.back().status;
  ASSERT_TRUE(std::isfinite(last.identified_effective_damping));
  EXPECT_EQ(last.identified_effective_damping, direct.damping_ratio());
  EXPECT_NEAR(last.identified_effective_damping, s.damping_ratio, 0.001);  // an actuator without delay
  EXPECT_EQ(last.predicted_effective_damping, 0.0123);
  EXPECT_TRUE(std::isnan(got.batches.front().status.identified_effective_damping)) << "before two periods";
}

TEST(TelemetryPublisher, ASubscriberThatJoinsMidRunGetsTheRecentPast) {
  // 15 s at 256 samples/s: 120 batches; the publisher keeps the last 80 (10 s) for late joiners.
  const hybrid_test::TestConfig config = sdof(15.0);
  TelemetryPublisher publisher(publisher_config(12));
  TestAssembly test(config, {{}, false, false, {}, nullptr, {&publisher}});
  publisher.start(run_info(test, config));
  const hybrid_test::TestRun run = test.finish(test.run({}, {}));  // published, not yet ended
  ASSERT_EQ(run.steps, 15 * 1024);
  // 120 full batches, and any a writer idle for 100 ms flushed part-filled.
  const std::uint64_t sent = publisher.batches_sent();
  ASSERT_GE(sent, 120u);

  TelemetrySubscriber late({test_domain(), loopback_xml(), 12});
  testing::Received got;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (got.batches.size() < 80 && std::chrono::steady_clock::now() < give_up) {
    late.wait(std::chrono::milliseconds(100));
    late.take(got.batches, got.events);
  }
  ASSERT_EQ(got.batches.size(), 80u);
  EXPECT_EQ(got.batches.front().sequence, sent - 80);
  EXPECT_EQ(got.batches.back().sequence, sent - 1);
  const TelemetryBatch& newest = got.batches.back();
  EXPECT_EQ(newest.samples[newest.count - 1].step, run.steps);  // steps count from 1
  ASSERT_FALSE(got.events.empty());
  EXPECT_EQ(got.events.front().kind, EventKind::kRunStarted);  // the events are all kept
  EXPECT_TRUE(late.publisher_alive());
}

// Compares what a run recorded, step for step (the fields the CSV and the criteria use).
void expect_same_records(const hybrid_test::TestRun& a, const hybrid_test::TestRun& b) {
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    const auto& x = a.records[i];
    const auto& y = b.records[i];
    ASSERT_EQ(x.step, y.step);
    ASSERT_EQ(x.measured_m[0], y.measured_m[0]) << "step " << x.step;
    ASSERT_EQ(x.command_m[0], y.command_m[0]) << "step " << x.step;
    ASSERT_EQ(x.displacement_m[0], y.displacement_m[0]) << "step " << x.step;
    ASSERT_EQ(x.limit_flags, y.limit_flags) << "step " << x.step;
  }
}

// Goes away after its first batches, from the recorder's own thread: as a browser closed
// while the test runs.
class SubscriberThatLeaves final : public coordinator::RecordObserver {
 public:
  explicit SubscriberThatLeaves(std::uint32_t test_id)
      : subscriber_(
            std::make_unique<TelemetrySubscriber>(TelemetrySubscriberConfig{test_domain(), loopback_xml(), test_id})) {}
  void observe(const coordinator::StepRecord& r) override {
    if (r.step == 4000) subscriber_.reset();
  }
  bool left() const { return !subscriber_; }

 private:
  std::unique_ptr<TelemetrySubscriber> subscriber_;
};

TEST(TelemetryPublisher, ASubscriberThatNeverReadsOrGoesAwayChangesNothingInTheRun) {
  const hybrid_test::TestConfig config = sdof(20.0);  // 160 batches: twice the readers' history
  const hybrid_test::TestRun alone = run_with(config, nullptr);
  TelemetrySubscriber never_reads({test_domain(), loopback_xml(), 13});
  SubscriberThatLeaves leaves(13);
  TelemetryPublisher publisher(publisher_config(13));
  ASSERT_TRUE(testing::wait_for_publisher(never_reads));
  const hybrid_test::TestRun watched = run_with(config, &publisher, {&leaves});
  EXPECT_TRUE(leaves.left());
  EXPECT_EQ(watched.outcome, alone.outcome);
  EXPECT_EQ(watched.steps, config.duration_s * config.control_rate_hz);
  EXPECT_EQ(watched.dropped_records, 0u);
  EXPECT_EQ(publisher.dropped_samples(), 0);  // a full reader never refuses a keep-last write
  EXPECT_GE(publisher.batches_sent(), 161u);  // 160 full, the ended status
  expect_same_records(alone, watched);
}

TEST(TelemetryPublisher, EventsFollowTheNodesLimitFlagsAndOperatorsEventsGoThrough) {
  TelemetrySubscriber subscriber({test_domain(), loopback_xml(), 14});
  TelemetryPublisher publisher(publisher_config(14));
  ASSERT_TRUE(testing::wait_for_publisher(subscriber));
  TelemetryRunInfo info;
  info.run_id = 77;
  info.steps_planned = 4;
  info.control_rate_hz = 1024.0;
  info.channels = 1;
  publisher.start(info);
  coordinator::StepRecord r;
  r.channels = 1;
  const std::uint32_t flags[] = {0, transport::kLimitStroke, transport::kLimitStroke, 0};
  for (int n = 0; n < 4; ++n) {
    r.step = n;
    r.limit_flags = flags[n];
    publisher.observe(r);
  }
  TelemetryEvent command;
  command.kind = EventKind::kOperatorCommand;
  set_text(command.text, "stop from monitor@lab");
  publisher.publish_event(command);
  publisher.end({"stopped: a coordinator limit acted", true});
  const testing::Received got = testing::collect_until_ended(subscriber);
  std::vector<std::string> limits;
  bool operator_seen = false;
  for (const TelemetryEvent& e : got.events) {
    EXPECT_EQ(e.run_id, 77u);
    EXPECT_EQ(e.test_id, 14u);
    if (e.kind == EventKind::kLimit) limits.emplace_back(e.text.data());
    if (e.kind == EventKind::kOperatorCommand) operator_seen = std::strcmp(e.text.data(), "stop from monitor@lab") == 0;
  }
  ASSERT_EQ(limits.size(), 3u);
  EXPECT_EQ(limits[0], "node limits acting: stroke");  // step 1
  EXPECT_EQ(limits[1], "node limits acting: none");    // step 3
  EXPECT_EQ(limits[2], "stopped: a coordinator limit acted");
  EXPECT_TRUE(operator_seen);
}

}  // namespace
}  // namespace rpsd::telemetry
