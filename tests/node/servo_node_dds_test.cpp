// Bad commands over DDS into a servo node: a raw Cyclone writer on the command topic, in the
// node's partition, publishes what a faulty or foreign coordinator could send (a duplicated,
// an older or out-of-order step, another test or site id, a wrong channel count, a NaN
// displacement or time); the node's endpoint takes each, its controller drops and counts it
// by reason, and the actuator never sees it.
#include <dds/dds.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <future>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "claimed_dds_domain.h"
#include "rpsd/node/servo_node_controller.h"
#include "rpsd/node/servo_node_loop.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/transport/dds_node_endpoint.h"
#include "rpsd/transport/dds_qos_profile.h"
#include "rpsd_messages.h"

namespace rpsd::node {
namespace {

using transport::CommandSample;
using transport::FeedbackSample;

constexpr std::uint32_t kTest = 61, kSite = 2;
constexpr std::uint64_t kRun = 0x61;

transport::DdsDomainConfig loopback() {
  return {::rpsd::testing::claimed_dds_domain(), std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/loopback.xml"};
}

// Moves to every command at once and reads it back.
class IdealActuator final : public servo::Actuator {
 public:
  int channels() const override { return 1; }
  void start(std::span<const double>) override {}
  servo::ActuatorStatus exchange(std::span<const double> command_m, double, servo::ActuatorReading& reading) override {
    sent.push_back(command_m[0]);
    reading.displacement_m[0] = command_m[0];
    reading.force_n[0] = 0.0;
    reading.fresh = true;
    return servo::ActuatorStatus::kOk;
  }
  std::vector<double> sent;
};

// A coordinator's side of the site without DdsLink's checks: the site's ports (command writer,
// feedback reader); it writes any command and takes every feedback sample.
class RawCoordinator {
 public:
  RawCoordinator(const transport::DdsParticipant& participant, std::uint32_t test_id, std::uint32_t site_id)
      : ports_(participant, test_id, site_id, participant.command_topic(), transport::stream_writer_qos({}),
               participant.feedback_topic(), transport::stream_reader_qos({})) {}
  bool wait_for_reader(double timeout_s) const {
    const std::int64_t until = realtime::monotonic_now_ns() + static_cast<std::int64_t>(timeout_s * 1e9);
    dds_publication_matched_status_t status{};
    while (dds_get_publication_matched_status(ports_.writer(), &status) >= 0 && status.current_count == 0) {
      if (realtime::monotonic_now_ns() > until) return false;
      dds_sleepfor(DDS_MSECS(10));
    }
    return status.current_count > 0;
  }
  void write(std::uint32_t test_id, std::uint32_t site_id, std::int64_t step, std::uint8_t channels, double x_m,
             double time_s = 0.0, std::uint64_t run_id = kRun) {
    rpsd_dds_Command wire{};
    wire.test_id = test_id;
    wire.site_id = site_id;
    wire.run_id = run_id;
    wire.step = step;
    wire.time_s = time_s;
    wire.channels = channels;
    wire.displacement_m[0] = x_m;
    ASSERT_GE(dds_write(ports_.writer(), &wire), 0);
  }
  // The steps of the feedback samples taken within `timeout_s`, until `count` of them.
  std::vector<std::int64_t> take_steps(std::size_t count, double timeout_s) {
    std::vector<std::int64_t> steps;
    const std::int64_t until = realtime::monotonic_now_ns() + static_cast<std::int64_t>(timeout_s * 1e9);
    rpsd_dds_Feedback wire{};
    void* samples[1] = {&wire};
    dds_sample_info_t info[1];
    while (steps.size() < count && realtime::monotonic_now_ns() < until) {
      if (dds_take(ports_.reader(), samples, info, 1, 1) > 0) {
        if (info[0].valid_data) {
          steps.push_back(wire.step);
          runs.push_back(wire.run_id);
        }
      } else {
        dds_sleepfor(DDS_MSECS(1));
      }
    }
    return steps;
  }
  std::vector<std::uint64_t> runs;  // the run each feedback sample taken named

 private:
  transport::DdsSitePorts ports_;
};

struct NodeOverDds : ::testing::Test {
  NodeOverDds()
      : coordinator_side(loopback()),
        node_side(loopback()),
        coordinator(coordinator_side, kTest, kSite),
        endpoint(node_side, {kTest, kSite, {}}),
        node(config(), actuator) {
    const double x0[] = {0.0};
    node.start(x0);
  }
  static ServoNodeConfig config() {
    ServoNodeConfig c;
    c.test_id = kTest;
    c.site_id = kSite;
    c.channels = 1;
    c.command_timeout_periods = 1000;  // the node must not hold while the test looks
    return c;
  }
  // The next command off the wire: accepted or dropped, then one control tick.
  CommandVerdict deliver(std::int64_t expected_step) {
    EXPECT_TRUE(endpoint.wait_for_command_until(realtime::monotonic_now_ns() + 5'000'000'000));
    CommandSample command;
    EXPECT_TRUE(endpoint.take_command(command));
    EXPECT_EQ(command.step, expected_step);  // reliable and in order: one sample each
    const CommandVerdict verdict = node.accept(command);
    node.tick(feedback);
    return verdict;
  }

  transport::DdsParticipant coordinator_side, node_side;
  RawCoordinator coordinator;
  transport::DdsNodeEndpoint endpoint;
  IdealActuator actuator;
  ServoNodeController node;
  FeedbackSample feedback;
};

TEST_F(NodeOverDds, EveryBadCommandIsDroppedCountedByReasonAndNeverApplied) {
  ASSERT_TRUE(coordinator.wait_for_reader(10.0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  coordinator.write(kTest, kSite, 0, 1, 0.001);
  EXPECT_EQ(deliver(0), CommandVerdict::kAccepted);
  coordinator.write(kTest, kSite, 0, 1, 0.009);  // duplicated step
  EXPECT_EQ(deliver(0), CommandVerdict::kNotNewer);
  coordinator.write(kTest, kSite, 3, 1, 0.002);
  EXPECT_EQ(deliver(3), CommandVerdict::kAccepted);
  coordinator.write(kTest, kSite, 2, 1, 0.009);  // older: late, or out of order
  EXPECT_EQ(deliver(2), CommandVerdict::kNotNewer);
  coordinator.write(kTest + 1, kSite, 4, 1, 0.009);  // another test's id, in this test's partition
  EXPECT_EQ(deliver(4), CommandVerdict::kWrongTestId);
  coordinator.write(kTest, kSite + 1, 5, 1, 0.009);  // another site's id
  EXPECT_EQ(deliver(5), CommandVerdict::kWrongSiteId);
  coordinator.write(kTest, kSite, 6, 2, 0.009);  // two channels for a one-channel node
  EXPECT_EQ(deliver(6), CommandVerdict::kWrongChannelCount);
  coordinator.write(kTest, kSite, 7, 1, nan);
  EXPECT_EQ(deliver(7), CommandVerdict::kNonFinite);
  coordinator.write(kTest, kSite, 8, 1, 0.009, inf);
  EXPECT_EQ(deliver(8), CommandVerdict::kNonFinite);

  // The actuator saw 1 mm, then 2 mm on every tick after: no bad command moved it.
  ASSERT_EQ(actuator.sent.size(), 9u);
  EXPECT_EQ(actuator.sent[0], 0.001);
  for (std::size_t i = 1; i < actuator.sent.size(); ++i) EXPECT_EQ(actuator.sent[i], i == 1 ? 0.001 : 0.002) << i;
  EXPECT_EQ(feedback.step, 3);  // the feedback still answers step 3
  const ServoNodeCounters& n = node.counters();
  EXPECT_EQ(n.accepted, 2u);
  EXPECT_EQ(n.applied, 2u);
  EXPECT_EQ(n.dropped(CommandVerdict::kNotNewer), 2u);
  EXPECT_EQ(n.dropped(CommandVerdict::kWrongTestId), 1u);
  EXPECT_EQ(n.dropped(CommandVerdict::kWrongSiteId), 1u);
  EXPECT_EQ(n.dropped(CommandVerdict::kWrongChannelCount), 1u);
  EXPECT_EQ(n.dropped(CommandVerdict::kNonFinite), 2u);
  EXPECT_EQ(n.dropped_total(), 7u);

  // A good command after all that is followed.
  coordinator.write(kTest, kSite, 9, 1, 0.003);
  EXPECT_EQ(deliver(9), CommandVerdict::kAccepted);
  EXPECT_EQ(actuator.sent.back(), 0.003);
  EXPECT_EQ(feedback.step, 9);
}

TEST_F(NodeOverDds, ANodeStartedMidTestTakesNoneOfItsCommands) {
  ASSERT_TRUE(coordinator.wait_for_reader(10.0));
  for (std::int64_t step = 1186; step < 1190; ++step) {
    coordinator.write(kTest, kSite, step, 1, 0.004);
    EXPECT_EQ(deliver(step), CommandVerdict::kJoinedMidTest);
  }
  for (double x : actuator.sent) EXPECT_EQ(x, 0.0);
  EXPECT_EQ(feedback.step, -1);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kJoinedMidTest), 4u);
}

// Lock-step as `rpsd servo-node` runs it: every command answered by one feedback sample of its
// step (on Cyclone's receive thread); once the loop has returned, a command moves nothing.
TEST_F(NodeOverDds, LockStepAnswersEveryCommandAndNothingAfterTheLoopEnds) {
  ASSERT_TRUE(coordinator.wait_for_reader(10.0));
  std::atomic<bool> stop{false};
  ServoNodeLoopOptions options;
  options.real_time = false;
  options.realtime.lock_memory = false;
  options.realtime.fifo_priority = 0;
  ServoNodeLoopReport report;
  std::thread loop([&] { report = run_servo_node_loop(node, endpoint, options, stop); });
  coordinator.take_steps(1000, 1.0);  // discovery of the feedback reader; nothing is sent yet
  for (std::int64_t step = 1; step <= 50; ++step) {
    coordinator.write(kTest, kSite, step, 1, 1e-4 * static_cast<double>(step));
    const auto got = coordinator.take_steps(1, 5.0);
    ASSERT_EQ(got.size(), 1u) << "no feedback for step " << step;
    EXPECT_EQ(got[0], step);
  }
  stop = true;
  loop.join();
  EXPECT_EQ(report.feedback_published, 50);
  EXPECT_EQ(report.first_command_tick, 0);
  EXPECT_EQ(report.last_command_tick, 49);
  ASSERT_EQ(actuator.sent.size(), 50u);
  EXPECT_EQ(actuator.sent.back(), 50e-4);

  coordinator.write(kTest, kSite, 51, 1, 0.009);
  EXPECT_TRUE(coordinator.take_steps(1, 0.3).empty());
  EXPECT_EQ(actuator.sent.size(), 50u);
}

ServoNodeLoopOptions lock_step_options() {
  ServoNodeLoopOptions options;
  options.real_time = false;
  options.realtime.lock_memory = false;
  options.realtime.fifo_priority = 0;
  options.realtime.keep_cpus_awake = false;
  return options;
}

// Issue 30: the node's heartbeat carries its actuator's newest reading, so that a coordinator
// calibrates a setup from it at rest. A node that has read nothing says so; one that has (the
// reading at rest noted after start, a command's exchange) carries it, in every state.
transport::DdsLinkConfig link_to_node() {
  transport::DdsLinkConfig c;
  c.test_id = kTest;
  c.site_id = kSite;
  c.run_id = kRun;  // the raw coordinator's: the node serving it does not refuse this link
  c.channels = 1;
  return c;
}

// Polls the node's heartbeats until one satisfies `done` (10 s: a bound against a hang).
template <class Done>
bool heartbeat_until(transport::DdsLink& link, Done done) {
  const std::int64_t until = realtime::monotonic_now_ns() + 10'000'000'000;
  while (realtime::monotonic_now_ns() < until) {
    link.wait_for_node(0.05);
    if (link.node_heartbeat() && done(*link.node_heartbeat())) return true;
  }
  return false;
}

TEST_F(NodeOverDds, TheHeartbeatSaysTheNodeHasReadNothingThenCarriesItsReadings) {
  ASSERT_TRUE(coordinator.wait_for_reader(10.0));
  std::atomic<bool> stop{false};
  std::thread loop([&] { run_servo_node_loop(node, endpoint, lock_step_options(), stop); });
  transport::DdsLink link(coordinator_side, link_to_node());
  ASSERT_TRUE(link.wait_for_node(10.0));
  ASSERT_TRUE(link.node_heartbeat().has_value());
  EXPECT_FALSE(link.node_heartbeat()->measured);  // lock-step, no command yet: nothing read
  coordinator.take_steps(1000, 0.5);              // discovery of the feedback reader
  coordinator.write(kTest, kSite, 0, 1, 0.0025);
  ASSERT_EQ(coordinator.take_steps(1, 5.0).size(), 1u);
  // The exchange read 2.5 mm: the next heartbeat says so.
  const bool carried = heartbeat_until(link, [](const transport::NodeHeartbeat& h) { return h.measured; });
  stop = true;
  loop.join();
  ASSERT_TRUE(carried);
  EXPECT_EQ(link.node_heartbeat()->displacement_m[0], 0.0025);
  EXPECT_EQ(link.node_heartbeat()->force_n[0], 0.0);
}

TEST_F(NodeOverDds, AReadingNotedAtRestIsInTheHeartbeatBeforeAnyCommand) {
  servo::ActuatorReading at_rest;
  at_rest.displacement_m[0] = 0.003;
  at_rest.force_n[0] = -1250.0;
  node.note_reading_at_rest(at_rest);
  std::atomic<bool> stop{false};
  std::thread loop([&] { run_servo_node_loop(node, endpoint, lock_step_options(), stop); });
  transport::DdsLink link(coordinator_side, link_to_node());
  const bool found = link.wait_for_node(10.0);
  stop = true;
  loop.join();
  ASSERT_TRUE(found);
  ASSERT_TRUE(link.node_heartbeat().has_value());
  const transport::NodeHeartbeat& h = *link.node_heartbeat();
  EXPECT_TRUE(h.measured);
  EXPECT_EQ(h.state, transport::NodeHeartbeat::kWaiting);
  EXPECT_EQ(h.displacement_m[0], 0.003);
  EXPECT_EQ(h.force_n[0], -1250.0);
  EXPECT_TRUE(actuator.sent.empty());  // read without moving it
}

// A coordinator that dies sends no end of run: after release_after_silence_s without a command
// of its run the node frees itself, and the next run (another coordinator, another writer)
// gets answers. Until then the node refuses the next run's commands.
TEST_F(NodeOverDds, ARunThatFellSilentFreesTheNodeForTheNext) {
  ASSERT_TRUE(coordinator.wait_for_reader(10.0));
  std::atomic<bool> stop{false};
  ServoNodeLoopOptions options = lock_step_options();
  options.release_after_silence_s = 1.0;
  ServoNodeLoopReport report;
  std::thread loop([&] { report = run_servo_node_loop(node, endpoint, options, stop); });
  coordinator.take_steps(1000, 0.5);  // discovery of the feedback reader
  for (std::int64_t step = 0; step < 3; ++step) {
    coordinator.write(kTest, kSite, step, 1, 1e-4);
    ASSERT_EQ(coordinator.take_steps(1, 5.0).size(), 1u);
  }
  EXPECT_EQ(coordinator.runs.back(), kRun);
  transport::DdsParticipant next_side(loopback());
  RawCoordinator next(next_side, kTest, kSite);
  ASSERT_TRUE(next.wait_for_reader(10.0));
  constexpr std::uint64_t kNextRun = 0x62;
  next.take_steps(1000, 0.3);
  next.write(kTest, kSite, 0, 1, 2e-4, 0.0, kNextRun);  // the node still serves kRun: refused
  EXPECT_TRUE(next.take_steps(1, 0.3).empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // silence beyond 1 s
  next.write(kTest, kSite, 1, 1, 2e-4, 0.0, kNextRun);
  const auto got = next.take_steps(1, 5.0);
  stop = true;
  loop.join();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], 1);
  EXPECT_EQ(next.runs.back(), kNextRun);
  EXPECT_EQ(node.counters().runs, 2u);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kOtherRun), 1u);
  std::vector<RunEvent::Kind> kinds;
  for (const auto& e : node.run_events()) kinds.push_back(e.kind);
  EXPECT_EQ(kinds, (std::vector<RunEvent::Kind>{RunEvent::Kind::kBound, RunEvent::Kind::kRefused,
                                                RunEvent::Kind::kReleasedAfterSilence, RunEvent::Kind::kBound}));
}

// A node at a very slow control rate (a 10 s period, its first tick 20 s away) stops within
// a fraction of a second of being asked, and at the end of its duration: the loop wakes at
// least every 50 ms whatever the period. The futures' 10 s are a bound against a hang.
TEST(SlowNode, StopsWhenAskedAndAtTheEndOfItsDurationWhateverItsRate) {
  transport::DdsParticipant participant(loopback());
  transport::DdsNodeEndpoint endpoint(participant, {kTest, kSite, {}});
  IdealActuator actuator;
  ServoNodeConfig c = NodeOverDds::config();
  c.control_period_s = 10.0;
  c.command_timeout_periods = 1;
  ServoNodeController node(c, actuator);
  const double x0[] = {0.0};
  node.start(x0);
  for (const bool real_time : {true, false}) {
    ServoNodeLoopOptions options = lock_step_options();
    options.real_time = real_time;
    std::atomic<bool> stop{false};
    auto stopped = std::async(std::launch::async, [&] { return run_servo_node_loop(node, endpoint, options, stop); });
    EXPECT_EQ(stopped.wait_for(std::chrono::milliseconds(300)), std::future_status::timeout);  // it serves
    stop = true;
    EXPECT_EQ(stopped.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "real time " << real_time;
    stopped.get();

    options.duration_s = 0.3;
    std::atomic<bool> never{false};
    auto ended = std::async(std::launch::async, [&] { return run_servo_node_loop(node, endpoint, options, never); });
    EXPECT_EQ(ended.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "real time " << real_time;
    ended.get();
  }
  EXPECT_EQ(actuator.sent.size(), 0u);  // no tick was due
}

}  // namespace
}  // namespace rpsd::node
