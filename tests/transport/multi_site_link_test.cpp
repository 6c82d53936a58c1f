#include "rpsd/transport/multi_site_link.h"

#include <gtest/gtest.h>

#include "rpsd/transport/in_process_link.h"

namespace rpsd::transport {
namespace {

// A node whose channel k measures 10 * site + command and reports its site in the status.
class EchoNode final : public CommandProcessor {
 public:
  explicit EchoNode(std::uint32_t site) : site_(site) {}
  bool process(const CommandSample& c, FeedbackSample& f) override {
    seen = c;
    f.test_id = c.test_id;
    f.site_id = c.site_id;
    f.step = c.step;
    f.channels = c.channels;
    for (int k = 0; k < c.channels; ++k) {
      f.displacement_m[k] = 10.0 * site_ + c.displacement_m[k];
      f.force_n[k] = -f.displacement_m[k];
    }
    f.status = site_ == 2 ? kNodeLimitActive : kNodeOk;
    return true;
  }
  CommandSample seen;

 private:
  std::uint32_t site_;
};

TEST(MultiSiteLink, RoutesEachChannelToItsSiteAndMergesTheFeedback) {
  EchoNode a(1), b(2);
  InProcessLink la(a), lb(b);
  MultiSiteLink link({{1, &la, {2, 0}}, {2, &lb, {1}}});
  EXPECT_EQ(link.channels(), 3);
  CommandSample c;
  c.test_id = 7;
  c.step = 4;
  c.channels = 3;
  c.displacement_m = {0.1, 0.2, 0.3};
  ASSERT_EQ(link.send(c), LinkStatus::kOk);
  EXPECT_EQ(a.seen.site_id, 1u);
  EXPECT_EQ(a.seen.channels, 2);
  EXPECT_DOUBLE_EQ(a.seen.displacement_m[0], 0.3);
  EXPECT_DOUBLE_EQ(a.seen.displacement_m[1], 0.1);
  EXPECT_EQ(b.seen.site_id, 2u);
  EXPECT_DOUBLE_EQ(b.seen.displacement_m[0], 0.2);
  FeedbackSample f;
  ASSERT_EQ(link.receive(f), LinkStatus::kOk);
  EXPECT_EQ(f.step, 4);
  EXPECT_EQ(f.channels, 3);
  EXPECT_DOUBLE_EQ(f.displacement_m[0], 10.1);
  EXPECT_DOUBLE_EQ(f.displacement_m[1], 20.2);
  EXPECT_DOUBLE_EQ(f.displacement_m[2], 10.3);
  EXPECT_DOUBLE_EQ(f.force_n[1], -20.2);
  EXPECT_EQ(f.status, kNodeLimitActive);  // one site's limit shows on the merged sample
}

// Mixed control: each channel's mode and force go to its site with its displacement.
TEST(MultiSiteLink, RoutesEachChannelsControlModeAndForceToItsSite) {
  EchoNode a(1), b(2);
  InProcessLink la(a), lb(b);
  MultiSiteLink link({{1, &la, {2, 0}}, {2, &lb, {1}}});
  CommandSample c;
  c.channels = 3;
  c.control_mode = {kDisplacementControl, kDisplacementControl, kForceControl};
  c.force_n = {0.0, 0.0, 250e3};
  ASSERT_EQ(link.send(c), LinkStatus::kOk);
  EXPECT_EQ(a.seen.control_mode[0], kForceControl);
  EXPECT_EQ(a.seen.force_n[0], 250e3);
  EXPECT_EQ(a.seen.control_mode[1], kDisplacementControl);
  EXPECT_EQ(b.seen.control_mode[0], kDisplacementControl);
  EXPECT_EQ(b.seen.force_n[0], 0.0);
}

// Each site gets the command's own fields and its channels, nothing of another site's.
TEST(MultiSiteLink, ASiteGetsEveryFieldOfTheCommandAndNoOtherSitesChannels) {
  EchoNode a(1), b(2);
  InProcessLink la(a), lb(b);
  MultiSiteLink link({{1, &la, {0}}, {2, &lb, {1}}});
  CommandSample c;
  c.test_id = 7;
  c.run_id = 0x1234'5678'9abc'def0ULL;
  c.step = 12;
  c.time_s = 0.5;
  c.control_period_s = 1.0 / 1024.0;
  c.end_of_run = true;
  c.channels = 2;
  c.displacement_m = {0.1, 0.2};
  c.control_mode = {kDisplacementControl, kForceControl};
  c.force_n = {0.0, 3e4};
  c.writer = 99;
  ASSERT_EQ(link.send(c), LinkStatus::kOk);
  for (const EchoNode* node : {&a, &b}) {
    EXPECT_EQ(node->seen.test_id, 7u);
    EXPECT_EQ(node->seen.run_id, c.run_id);
    EXPECT_EQ(node->seen.step, 12);
    EXPECT_EQ(node->seen.time_s, 0.5);
    EXPECT_EQ(node->seen.control_period_s, 1.0 / 1024.0);
    EXPECT_TRUE(node->seen.end_of_run);
    EXPECT_EQ(node->seen.writer, 99u);
    EXPECT_EQ(node->seen.channels, 1);
    // The entry beyond the site's one channel: 0, not the other site's channel 1.
    EXPECT_EQ(node->seen.displacement_m[1], 0.0);
    EXPECT_EQ(node->seen.control_mode[1], kDisplacementControl);
    EXPECT_EQ(node->seen.force_n[1], 0.0);
  }
  EXPECT_EQ(a.seen.displacement_m[0], 0.1);
  EXPECT_EQ(b.seen.displacement_m[0], 0.2);
  EXPECT_EQ(b.seen.control_mode[0], kForceControl);
  EXPECT_EQ(b.seen.force_n[0], 3e4);
}

TEST(InProcessLink, HandsBackEveryFieldOfTheNodesFeedbackAndItsChannels) {
  // A node that answers with every field set, and its one channel.
  class FullNode final : public CommandProcessor {
   public:
    bool process(const CommandSample&, FeedbackSample& f) override {
      f.test_id = 3;
      f.site_id = 4;
      f.run_id = 5;
      f.step = 6;
      f.time_s = 0.25;
      f.channels = 1;
      f.displacement_m[0] = 0.01;
      f.force_n[0] = -2e3;
      f.round_trip_ns[0] = 17;
      f.status = kNodeLimitActive | kNodeHolding;
      f.limit_flags = kLimitStroke;
      return true;
    }
  } node;
  InProcessLink link(node);
  ASSERT_EQ(link.send(CommandSample{}), LinkStatus::kOk);
  FeedbackSample f;
  ASSERT_EQ(link.receive(f), LinkStatus::kOk);
  EXPECT_EQ(f.test_id, 3u);
  EXPECT_EQ(f.site_id, 4u);
  EXPECT_EQ(f.run_id, 5u);
  EXPECT_EQ(f.step, 6);
  EXPECT_EQ(f.time_s, 0.25);
  EXPECT_EQ(f.channels, 1);
  EXPECT_EQ(f.displacement_m[0], 0.01);
  EXPECT_EQ(f.force_n[0], -2e3);
  EXPECT_EQ(f.round_trip_ns[0], 17);
  EXPECT_EQ(f.status, kNodeLimitActive | kNodeHolding);
  EXPECT_EQ(f.limit_flags, kLimitStroke);
  EXPECT_EQ(link.receive(f), LinkStatus::kTimeout);  // one feedback per command
}

TEST(Messages, EveryChannelOfACommandIsInDisplacementControlUnlessItSaysOtherwise) {
  const CommandSample c;
  for (int k = 0; k < kMaxChannels; ++k) {
    EXPECT_EQ(c.control_mode[k], kDisplacementControl);
    EXPECT_EQ(c.force_n[k], 0.0);
  }
}

// A link whose node has not answered yet: it leaves the feedback untouched (Link::receive).
class SilentLink final : public Link {
 public:
  LinkStatus send(const CommandSample&) override { return LinkStatus::kOk; }
  LinkStatus receive(FeedbackSample&) override { return LinkStatus::kTimeout; }
};

TEST(MultiSiteLink, ASiteThatNeverAnsweredIsAtStepMinusOneAndNotGivenAnotherSitesValues) {
  EchoNode a(1);
  InProcessLink la(a);
  SilentLink lb;
  MultiSiteLink link({{1, &la, {0}}, {2, &lb, {1}}});
  CommandSample c;
  c.step = 0;
  c.channels = 2;
  c.displacement_m = {0.1, 0.2};
  ASSERT_EQ(link.send(c), LinkStatus::kOk);
  FeedbackSample f;
  f.displacement_m[1] = 0.5;  // what the caller holds for channel 1 (the start)
  f.force_n[1] = 7.0;
  EXPECT_EQ(link.receive(f), LinkStatus::kTimeout);
  EXPECT_EQ(f.step, -1);
  EXPECT_DOUBLE_EQ(f.displacement_m[0], 10.1);
  EXPECT_DOUBLE_EQ(f.displacement_m[1], 0.5);  // not site 1's 10.1
  EXPECT_DOUBLE_EQ(f.force_n[1], 7.0);
}

// One site owning every channel in order (a test of one site): its link writes the merged
// sample itself, which says what several sites' would: no site, the test's channels, the
// caller's run; before the site answers, step -1 and the values the caller held.
TEST(MultiSiteLink, OneSiteOwningEveryChannelInOrderHandsBackWhatAMergeWould) {
  EchoNode a(2);
  InProcessLink la(a);
  MultiSiteLink link({{2, &la, {0, 1}}});
  FeedbackSample f;
  f.run_id = 77;  // the caller's, which the link does not set
  f.displacement_m = {0.5, 0.6};
  f.test_id = 9;
  EXPECT_EQ(link.receive(f), LinkStatus::kTimeout);  // nothing sent yet
  EXPECT_EQ(f.step, -1);
  EXPECT_EQ(f.status, kNodeOk);
  EXPECT_EQ(f.channels, 2);
  EXPECT_EQ(f.test_id, 9u);
  EXPECT_EQ(f.displacement_m[1], 0.6);

  CommandSample c;
  c.test_id = 3;
  c.run_id = 5;
  c.step = 8;
  c.channels = 2;
  c.displacement_m = {0.1, 0.2};
  ASSERT_EQ(link.send(c), LinkStatus::kOk);
  EXPECT_EQ(a.seen.site_id, 2u);
  EXPECT_EQ(a.seen.run_id, 5u);
  ASSERT_EQ(link.receive(f), LinkStatus::kOk);
  EXPECT_EQ(f.step, 8);
  EXPECT_EQ(f.test_id, 3u);
  EXPECT_EQ(f.site_id, 0u);  // the node's is 2: a merged sample names no site
  EXPECT_EQ(f.run_id, 77u);
  EXPECT_EQ(f.channels, 2);
  EXPECT_EQ(f.status, kNodeLimitActive);
  EXPECT_DOUBLE_EQ(f.displacement_m[0], 20.1);
  EXPECT_DOUBLE_EQ(f.force_n[1], -20.2);
}

TEST(MultiSiteLink, RejectsChannelsOwnedTwiceOrByNobody) {
  EchoNode a(1);
  InProcessLink la(a), lb(a);
  EXPECT_THROW(MultiSiteLink({{1, &la, {0, 1}}, {2, &lb, {1}}}), std::invalid_argument);
  EXPECT_THROW(MultiSiteLink({{1, &la, {0, 2}}}), std::invalid_argument);
  EXPECT_THROW(MultiSiteLink({{1, nullptr, {0}}}), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::transport
