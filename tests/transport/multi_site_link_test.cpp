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

TEST(MultiSiteLink, RejectsChannelsOwnedTwiceOrByNobody) {
  EchoNode a(1);
  InProcessLink la(a), lb(a);
  EXPECT_THROW(MultiSiteLink({{1, &la, {0, 1}}, {2, &lb, {1}}}), std::invalid_argument);
  EXPECT_THROW(MultiSiteLink({{1, &la, {0, 2}}}), std::invalid_argument);
  EXPECT_THROW(MultiSiteLink({{1, nullptr, {0}}}), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::transport
