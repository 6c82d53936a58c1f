// The DDS link between a coordinator and a node participant in one process, over the
// loopback configuration shipped in transport/config/.
#include "rpsd/transport/dds_link.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "dds_test_peers.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/transport/dds_node_endpoint.h"

namespace rpsd::transport {
namespace {

using testing::connect;
using testing::connect_with;
using testing::link_config;
using testing::loopback;
using testing::node_config;

// Answers every command of its site with x = 2 u, F = -u, until stopped.
void echo(DdsNodeEndpoint& node, std::uint32_t site, const std::atomic<bool>& stop, int max_answers = 1 << 30) {
  CommandSample c;
  int answered = 0;
  while (!stop && answered < max_answers) {
    if (!node.wait_for_command_until(realtime::monotonic_now_ns() + 20'000'000)) continue;
    while (node.take_command(c) && answered < max_answers) {
      FeedbackSample f;
      f.test_id = c.test_id;
      f.site_id = site;
      f.run_id = c.run_id;
      f.step = c.step;
      f.time_s = c.time_s;
      f.channels = c.channels;
      for (int k = 0; k < c.channels; ++k) {
        f.displacement_m[k] = 2.0 * c.displacement_m[k];
        f.force_n[k] = -c.displacement_m[k];
      }
      node.publish(f);
      ++answered;
    }
  }
}

TEST(DdsLink, LockStepRoundTripsCarryEveryStepAndMeasureTheirLatency) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(11, 3, 2));
  DdsNodeEndpoint node(node_side, node_config(11, 3));
  ASSERT_TRUE(connect(link, node, 11, 3));
  std::atomic<bool> stop{false};
  std::thread responder([&] { echo(node, 3, stop); });
  for (int step = 0; step < 200; ++step) {
    CommandSample c;
    c.step = step;
    c.channels = 2;
    c.displacement_m[0] = 1e-3 * step;
    c.displacement_m[1] = -1e-3 * step;
    ASSERT_EQ(link.send(c), LinkStatus::kOk);
    FeedbackSample f;
    ASSERT_EQ(link.receive(f), LinkStatus::kOk) << "step " << step;
    EXPECT_EQ(f.step, step);
    EXPECT_EQ(f.test_id, 11u);
    EXPECT_DOUBLE_EQ(f.displacement_m[0], 2e-3 * step);
    EXPECT_DOUBLE_EQ(f.force_n[1], 1e-3 * step);
    EXPECT_GT(f.round_trip_ns[0], 0);
    EXPECT_EQ(f.round_trip_ns[0], f.round_trip_ns[1]);
  }
  stop = true;
  responder.join();
  EXPECT_EQ(link.counters().sent, 200);
  EXPECT_EQ(link.counters().received, 200);
  EXPECT_EQ(link.counters().late, 0);
}

// Lock-step with a busy wait: every step still carried; a node slower than the busy wait is
// still waited for (on the waitset), and a prompt one is picked up without sleeping at all
// on some steps at least (all 200 answers taking longer than 10 ms would fail this).
TEST(DdsLink, BusyWaitCarriesEveryStepAndFallsBackToWaiting) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLinkConfig config = link_config(12, 1, 1);
  config.busy_wait_s = 0.01;
  DdsLink link(coordinator, config);
  DdsNodeEndpoint node(node_side, node_config(12, 1));
  ASSERT_TRUE(connect(link, node, 12, 1));
  std::atomic<bool> stop{false};
  std::thread responder([&] { echo(node, 1, stop); });
  const auto exchange = [&](int step) {
    CommandSample c;
    c.step = step;
    c.channels = 1;
    c.displacement_m[0] = 1e-3 * step;
    ASSERT_EQ(link.send(c), LinkStatus::kOk);
    FeedbackSample f;
    ASSERT_EQ(link.receive(f), LinkStatus::kOk) << "step " << step;
    EXPECT_EQ(f.step, step);
    EXPECT_DOUBLE_EQ(f.displacement_m[0], 2e-3 * step);
  };
  for (int step = 0; step < 200; ++step) exchange(step);
  EXPECT_LT(link.counters().waits, 200);
  stop = true;
  responder.join();

  // A node that answers after 30 ms: the 10 ms busy wait runs out, the link sleeps and gets it.
  stop = false;
  std::thread slow([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    echo(node, 1, stop, 1);
  });
  const auto waits_before = link.counters().waits;
  exchange(200);
  EXPECT_GE(link.counters().waits, waits_before + 1);
  stop = true;
  slow.join();
  EXPECT_EQ(link.counters().received, 201);
  EXPECT_EQ(link.counters().late, 0);
}

// Discovery ends on the two sides at different times; a command sent before the node's reader
// knows the coordinator's writer is lost. So the link waits for the node's heartbeat saying
// it has matched the coordinator, from the node of its own test and site.
TEST(DdsLink, WaitsForTheNodesWordThatItFoundTheCoordinator) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(61, 1, 1));
  DdsNodeEndpoint node(node_side, node_config(61, 1));
  const std::int64_t until = realtime::monotonic_now_ns() + 10'000'000'000;
  while (!node.coordinator_matched() && realtime::monotonic_now_ns() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(node.coordinator_matched());
  EXPECT_FALSE(link.wait_for_node(0.5));          // matched both ways, but no word from the node
  EXPECT_FALSE(connect(link, node, 61, 9, 0.5));  // a heartbeat claiming another site
  EXPECT_TRUE(connect(link, node, 61, 1));
}

// Issue 30: a node's heartbeat carries each channel's newest measured displacement and force
// and whether they are a measurement, so that the coordinator calibrates a setup's actuators
// from them at rest; every field arrives as sent.
TEST(DdsLink, AHeartbeatCarriesTheNodesReadingsAndWhetherTheyAreMeasured) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(91, 1, 3));
  DdsNodeEndpoint node(node_side, node_config(91, 1));
  EXPECT_FALSE(link.node_heartbeat().has_value());  // nothing heard yet
  NodeHeartbeat h;
  h.test_id = 91;
  h.site_id = 1;
  h.channels = 3;
  h.state = NodeHeartbeat::kHolding;
  h.control_period_s = DdsQosConfig{}.control_period_s;
  h.measured = true;
  h.displacement_m = {0.003, -1.25e-4, 0.0421, 0, 0, 0, 0, 7.5};
  h.force_n = {-1520.5, 3.0e4, 0.125, 0, 0, 0, 0, -2.0};
  ASSERT_TRUE(connect_with(link, node, h));
  ASSERT_TRUE(link.node_heartbeat().has_value());
  const NodeHeartbeat& heard = *link.node_heartbeat();
  EXPECT_TRUE(heard.measured);
  EXPECT_EQ(heard.state, NodeHeartbeat::kHolding);
  EXPECT_EQ(heard.channels, 3);
  EXPECT_EQ(heard.displacement_m, h.displacement_m);
  EXPECT_EQ(heard.force_n, h.force_n);

  // A node that has read nothing yet says so.
  DdsLink unread(coordinator, link_config(91, 2, 1));
  DdsNodeEndpoint node_unread(node_side, node_config(91, 2));
  h.site_id = 2;
  h.channels = 1;
  h.measured = false;
  ASSERT_TRUE(connect_with(unread, node_unread, h));
  ASSERT_TRUE(unread.node_heartbeat().has_value());
  EXPECT_FALSE(unread.node_heartbeat()->measured);
}

TEST(DdsLink, TwoTestsOnOneNetworkNeverSeeEachOther) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(21, 1, 1));
  DdsNodeEndpoint other_test(node_side, node_config(22, 1));
  DdsNodeEndpoint other_site(node_side, node_config(21, 2));
  EXPECT_FALSE(link.wait_for_node(1.0));
  CommandSample c;
  c.channels = 1;
  link.send(c);
  EXPECT_FALSE(other_test.wait_for_command_until(realtime::monotonic_now_ns() + 300'000'000));
  EXPECT_FALSE(other_site.wait_for_command_until(realtime::monotonic_now_ns() + 10'000'000));
  CommandSample got;
  EXPECT_FALSE(other_test.take_command(got));
  EXPECT_FALSE(other_site.take_command(got));
}

TEST(DdsLink, FeedbackWithAForeignSiteIdOrChannelCountIsDroppedAndCounted) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(31, 1, 1, 0.3));
  DdsNodeEndpoint node(node_side, node_config(31, 1));
  ASSERT_TRUE(connect(link, node, 31, 1));
  CommandSample c;
  c.channels = 1;
  c.step = 0;
  link.send(c);
  FeedbackSample bad;
  bad.test_id = 31;
  bad.run_id = link.run_id();
  bad.site_id = 9;  // in the partition of site 1, but claiming another site
  bad.channels = 1;
  node.publish(bad);
  bad.site_id = 1;
  bad.channels = 3;
  node.publish(bad);
  FeedbackSample f;
  EXPECT_EQ(link.receive(f), LinkStatus::kTimeout);
  EXPECT_EQ(link.counters().wrong_test_or_site, 1);
  EXPECT_EQ(link.counters().wrong_channels, 1);
  EXPECT_EQ(link.counters().received, 0);
  EXPECT_EQ(link.counters().late, 1);
}

TEST(DdsLink, FeedbackOfAnotherTestOrAnOlderStepIsDroppedAndCounted) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(51, 1, 1, 0.3));
  DdsNodeEndpoint node(node_side, node_config(51, 1));
  ASSERT_TRUE(connect(link, node, 51, 1));
  CommandSample c;
  c.channels = 1;
  c.step = 5;
  link.send(c);
  FeedbackSample f;
  f.test_id = 51;
  f.site_id = 1;
  f.run_id = link.run_id();
  f.channels = 1;
  f.step = 5;
  f.displacement_m[0] = 0.005;
  FeedbackSample foreign = f;
  foreign.test_id = 52;  // in the partition of test 51, but claiming test 52
  foreign.displacement_m[0] = 1.0;
  node.publish(foreign);
  node.publish(f);
  FeedbackSample older = f;
  older.step = 4;  // late, or out of order
  older.displacement_m[0] = 1.0;
  node.publish(older);
  node.publish(f);  // duplicated: the same step again is not older (a node re-reports its newest step)
  FeedbackSample got;
  ASSERT_EQ(link.receive(got), LinkStatus::kOk);
  EXPECT_EQ(got.step, 5);
  EXPECT_EQ(got.displacement_m[0], 0.005);
  // The link takes everything waiting on its next receive: give the last two time to arrive.
  c.step = 6;
  link.send(c);
  EXPECT_EQ(link.receive(got), LinkStatus::kTimeout);
  EXPECT_EQ(got.step, 5);
  EXPECT_EQ(got.displacement_m[0], 0.005);  // never the foreign or the older sample's 1 m
  EXPECT_EQ(link.counters().wrong_test_or_site, 1);
  EXPECT_EQ(link.counters().older_step, 1);
  EXPECT_EQ(link.counters().received, 2);
}

// Real time: answers to steps 1, 2 and 3 are all waiting when the coordinator looks. The
// answer to step 1 is an alarm; the link hands it back rather than the newest, whatever comes.
FeedbackSample newest_after_an_alarm(std::uint32_t test, const FeedbackSample& alarm) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(test, 1, 1, 0.2));
  DdsNodeEndpoint node(node_side, node_config(test, 1));
  EXPECT_TRUE(connect(link, node, test, 1));
  CommandSample c;
  c.channels = 1;
  c.step = 3;
  link.send(c);
  FeedbackSample f;
  f.test_id = test;
  f.site_id = 1;
  f.run_id = link.run_id();
  f.channels = 1;
  for (std::int64_t step = 1; step <= 3; ++step) {
    f.step = step;
    f.displacement_m[0] = 0.001 * step;
    FeedbackSample answer = step == 1 ? alarm : f;
    answer.run_id = link.run_id();
    node.publish(answer);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // all three in the reader
  FeedbackSample got;
  EXPECT_EQ(link.receive(got), LinkStatus::kTimeout);  // step 1 is not the step sent
  c.step = 4;
  link.send(c);
  f.step = 4;
  node.publish(f);
  FeedbackSample again;
  EXPECT_EQ(link.receive(again), LinkStatus::kTimeout);  // still held on the next receive
  EXPECT_EQ(again.step, got.step);
  EXPECT_EQ(link.counters().received, 4);
  return got;
}

// The answer of test `test`, site 1, to step 1; the caller makes it an alarm.
FeedbackSample answer_to_step_1(std::uint32_t test) {
  FeedbackSample f;
  f.test_id = test;
  f.site_id = 1;
  f.channels = 1;
  f.step = 1;
  return f;
}

TEST(DdsLink, ANonFiniteMeasurementIsHeldEvenWhenNewerAnswersFollowIt) {
  FeedbackSample alarm = answer_to_step_1(71);
  alarm.force_n[0] = std::numeric_limits<double>::quiet_NaN();
  const FeedbackSample got = newest_after_an_alarm(71, alarm);
  EXPECT_EQ(got.step, 1);
  EXPECT_TRUE(std::isnan(got.force_n[0]));
}

TEST(DdsLink, ANodeFaultIsHeldEvenWhenNewerAnswersFollowIt) {
  FeedbackSample alarm = answer_to_step_1(72);
  alarm.status = kNodeFault;
  const FeedbackSample got = newest_after_an_alarm(72, alarm);
  EXPECT_EQ(got.step, 1);
  EXPECT_EQ(got.status & kNodeFault, kNodeFault);
}

TEST(DdsLink, ARealTimeDeadlineEndsTheWaitAndHandsBackTheNewestSample) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(41, 1, 1, 5.0));
  DdsNodeEndpoint node(node_side, node_config(41, 1));
  ASSERT_TRUE(connect(link, node, 41, 1));
  std::atomic<bool> stop{false};
  std::thread responder([&] { echo(node, 1, stop, 1); });  // answers step 0 only
  CommandSample c;
  c.channels = 1;
  c.displacement_m[0] = 0.25;
  link.send(c);
  FeedbackSample f;
  ASSERT_EQ(link.receive(f), LinkStatus::kOk);
  c.step = 1;
  c.displacement_m[0] = 0.5;
  link.send(c);
  const std::int64_t t0 = realtime::monotonic_now_ns();
  link.set_receive_deadline_ns(t0 + 50'000'000);
  f = FeedbackSample{};
  EXPECT_EQ(link.receive(f), LinkStatus::kTimeout);
  EXPECT_GE(realtime::monotonic_now_ns() - t0, 50'000'000);  // waited for the deadline...
  EXPECT_EQ(f.step, 0);                                      // ...and returned step 0's sample
  EXPECT_DOUBLE_EQ(f.displacement_m[0], 0.5);
  stop = true;
  responder.join();
}

// Identity. A node serves one run at a time and says which (heartbeat, feedback); the link
// refuses a run its site's node will not serve, before the first command when the heartbeat
// says so, and uses only its own run's feedback from the node that answers it.

TEST(DdsLink, EveryCommandCarriesTheRunAndTheControlPeriod) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(81, 1, 1));
  DdsNodeEndpoint node(node_side, node_config(81, 1));
  ASSERT_TRUE(connect(link, node, 81, 1));
  EXPECT_NE(link.run_id(), 0u);
  DdsLink other(coordinator, link_config(81, 2, 1));
  EXPECT_NE(other.run_id(), link.run_id());  // drawn at random for each
  CommandSample c;
  c.channels = 1;
  c.step = 3;
  link.send(c);
  ASSERT_TRUE(node.wait_for_command_until(realtime::monotonic_now_ns() + 5'000'000'000));
  CommandSample got;
  ASSERT_TRUE(node.take_command(got));
  EXPECT_EQ(got.run_id, link.run_id());
  EXPECT_EQ(got.control_period_s, 1.0 / 1024.0);
  EXPECT_FALSE(got.end_of_run);
  EXPECT_NE(got.writer, 0u);  // the node's endpoint names the writer
  const std::uint64_t writer = got.writer;
  link.end_run();
  ASSERT_TRUE(node.wait_for_command_until(realtime::monotonic_now_ns() + 5'000'000'000));
  ASSERT_TRUE(node.take_command(got));
  EXPECT_TRUE(got.end_of_run);
  EXPECT_EQ(got.run_id, link.run_id());
  EXPECT_EQ(got.step, 4);
  EXPECT_EQ(got.writer, writer);
}

// Mixed control: each channel's control mode and force cross DDS with its displacement.
TEST(DdsLink, ACommandCarriesEachChannelsControlModeAndForce) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(82, 1, 2));
  DdsNodeEndpoint node(node_side, node_config(82, 1));
  ASSERT_TRUE(connect(link, node, 82, 1));
  CommandSample c;
  c.channels = 2;
  c.step = 1;
  c.displacement_m = {0.01, -0.02};
  c.control_mode = {kDisplacementControl, kForceControl};
  c.force_n = {0.0, -1.5e5};
  link.send(c);
  ASSERT_TRUE(node.wait_for_command_until(realtime::monotonic_now_ns() + 5'000'000'000));
  CommandSample got;
  ASSERT_TRUE(node.take_command(got));
  EXPECT_EQ(got.displacement_m[1], -0.02);
  EXPECT_EQ(got.control_mode[0], kDisplacementControl);
  EXPECT_EQ(got.control_mode[1], kForceControl);
  EXPECT_EQ(got.force_n[1], -1.5e5);
}

TEST(DdsLink, ANodeServingAnotherRunRefusesTheRunBeforeItsFirstCommand) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(82, 1, 1));
  DdsNodeEndpoint node(node_side, node_config(82, 1));
  EXPECT_FALSE(connect(link, node, 82, 1, 10.0, 0xabc));
  EXPECT_EQ(link.refusal().kind, NodeRefusal::Kind::kServingOtherRun);
  EXPECT_EQ(link.refusal().serving_run_id, 0xabcu);
  EXPECT_EQ(link.refusal_text(), "site 1 is serving another run (run 0000000000000abc; this run is " +
                                     run_id_text(link.run_id()) + "): a node serves one run at a time");
  CommandSample c;
  c.channels = 1;
  link.send(c);
  FeedbackSample f;
  EXPECT_EQ(link.receive(f), LinkStatus::kRefused);
}

TEST(DdsLink, ANodeServingThisRunIsReady) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(83, 1, 1));
  DdsNodeEndpoint node(node_side, node_config(83, 1));
  EXPECT_TRUE(connect(link, node, 83, 1, 10.0, link.run_id()));
  EXPECT_EQ(link.refusal().kind, NodeRefusal::Kind::kNone);
  EXPECT_EQ(link.refusal_text(), "");
}

TEST(DdsLink, ANodeAtAnotherControlRateRefusesTheRun) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(84, 2, 1));
  DdsNodeEndpoint node(node_side, node_config(84, 2));
  EXPECT_FALSE(connect(link, node, 84, 2, 10.0, 0, 1.0 / 512.0));
  EXPECT_EQ(link.refusal().kind, NodeRefusal::Kind::kRateMismatch);
  EXPECT_EQ(link.refusal_text(),
            "site 2 runs at 512 Hz and this test at 1024 Hz (control periods 0.00195312 s and 0.000976562 s): node and "
            "coordinator must run at one rate");
  DdsLink slow(coordinator, link_config(84, 3, 1));
  DdsNodeEndpoint node_at_1_hz(node_side, node_config(84, 3));
  EXPECT_FALSE(connect(slow, node_at_1_hz, 84, 3, 10.0, 0, 1.0));
  EXPECT_EQ(slow.refusal_text().rfind("site 3 runs at 1 Hz and this test at 1024 Hz", 0), 0u) << slow.refusal_text();
}

// Two coordinators passed the start check together; the node took the other's first command.
// Its feedback names the other run: this run stops at once, never using the measurement,
// also when the other run is steps ahead (its steps are not this run's "impossible" ones).
TEST(DdsLink, FeedbackOfAnotherRunRefusesTheRunAtOnce) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(85, 1, 1, 30.0));
  DdsNodeEndpoint node(node_side, node_config(85, 1));
  ASSERT_TRUE(connect(link, node, 85, 1));
  CommandSample c;
  c.channels = 1;
  link.send(c);
  FeedbackSample theirs;
  theirs.test_id = 85;
  theirs.site_id = 1;
  theirs.run_id = 0xd0d0;
  theirs.channels = 1;
  theirs.step = 500;
  theirs.displacement_m[0] = 1.0;
  node.publish(theirs);
  FeedbackSample f;
  f.displacement_m[0] = 0.25;
  EXPECT_EQ(link.receive(f), LinkStatus::kRefused);  // not a 30 s timeout
  EXPECT_EQ(f.displacement_m[0], 0.25);              // their measurement unused
  EXPECT_EQ(link.counters().other_run, 1);
  EXPECT_EQ(link.counters().impossible_step, 0);
  EXPECT_EQ(link.counters().received, 0);
  EXPECT_EQ(link.refusal().serving_run_id, 0xd0d0u);
}

// The node serving no run (before it took this run's first command) is not this run's answer.
TEST(DdsLink, FeedbackOfANodeServingNoRunIsNotUsed) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(86, 1, 1, 0.3));
  DdsNodeEndpoint node(node_side, node_config(86, 1));
  ASSERT_TRUE(connect(link, node, 86, 1));
  CommandSample c;
  c.channels = 1;
  link.send(c);
  FeedbackSample none;
  none.test_id = 86;
  none.site_id = 1;
  none.channels = 1;
  none.step = 0;
  none.displacement_m[0] = 1.0;
  node.publish(none);
  FeedbackSample f;
  EXPECT_EQ(link.receive(f), LinkStatus::kTimeout);
  EXPECT_EQ(link.counters().no_run, 1);
  EXPECT_EQ(link.counters().received, 0);
  EXPECT_EQ(link.refusal().kind, NodeRefusal::Kind::kNone);
}

// Once its node has answered, the link uses that writer's feedback only: another writer in the
// site's partition (a second node, a forger) is counted, never used, and cannot end the run by
// claiming another.
TEST(DdsLink, OnceItsNodeAnsweredTheLinkUsesNoOtherWriter) {
  DdsParticipant coordinator(loopback()), node_side(loopback()), intruder_side(loopback());
  DdsLink link(coordinator, link_config(87, 1, 1, 5.0));
  DdsNodeEndpoint node(node_side, node_config(87, 1));
  DdsNodeEndpoint intruder(intruder_side, node_config(87, 1));
  ASSERT_TRUE(connect(link, node, 87, 1));
  const std::int64_t until = realtime::monotonic_now_ns() + 10'000'000'000;
  while (!intruder.coordinator_matched() && realtime::monotonic_now_ns() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(intruder.coordinator_matched());
  FeedbackSample f;
  f.test_id = 87;
  f.site_id = 1;
  f.run_id = link.run_id();
  f.channels = 1;
  CommandSample c;
  c.channels = 1;
  link.send(c);
  f.displacement_m[0] = 0.001;
  node.publish(f);
  FeedbackSample got;
  ASSERT_EQ(link.receive(got), LinkStatus::kOk);
  c.step = 1;
  link.send(c);
  FeedbackSample forged = f;
  forged.step = 1;
  forged.displacement_m[0] = 1.0;
  intruder.publish(forged);
  forged.run_id = 0xbad;
  intruder.publish(forged);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // both in the link's reader first
  f.step = 1;
  f.displacement_m[0] = 0.002;
  node.publish(f);
  ASSERT_EQ(link.receive(got), LinkStatus::kOk);
  EXPECT_EQ(got.displacement_m[0], 0.002);
  EXPECT_EQ(link.counters().unknown_writer, 2);
  EXPECT_EQ(link.counters().other_run, 0);
  EXPECT_EQ(link.refusal().kind, NodeRefusal::Kind::kNone);
}

// No node can answer a step not sent yet: such a sample (step 9 x 10^18) is dropped and
// counted, and the true answers after it are used, not taken for older ones.
TEST(DdsLink, FeedbackOfAStepNotSentYetIsDropped) {
  DdsParticipant coordinator(loopback()), node_side(loopback());
  DdsLink link(coordinator, link_config(88, 1, 1, 5.0));
  DdsNodeEndpoint node(node_side, node_config(88, 1));
  ASSERT_TRUE(connect(link, node, 88, 1));
  FeedbackSample f;
  f.test_id = 88;
  f.site_id = 1;
  f.run_id = link.run_id();
  f.channels = 1;
  CommandSample c;
  c.channels = 1;
  for (std::int64_t step = 0; step < 3; ++step) {
    c.step = step;
    link.send(c);
    if (step == 1) {
      FeedbackSample ahead = f;
      ahead.step = 9'000'000'000'000'000'000;
      ahead.displacement_m[0] = 1.0;
      node.publish(ahead);
    }
    f.step = step;
    f.displacement_m[0] = 0.001 * static_cast<double>(step);
    node.publish(f);
    FeedbackSample got;
    ASSERT_EQ(link.receive(got), LinkStatus::kOk) << step;
    EXPECT_EQ(got.step, step);
    EXPECT_EQ(got.displacement_m[0], 0.001 * static_cast<double>(step));
  }
  EXPECT_EQ(link.counters().impossible_step, 1);
  EXPECT_EQ(link.counters().older_step, 0);
}

}  // namespace
}  // namespace rpsd::transport
