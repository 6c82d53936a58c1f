// The receiving half of the DDS fast path allocates nothing on the calling thread once
// running: DdsLink::receive (take, waitset wait, the checks) on the coordinator's loop and
// DdsNodeEndpoint::take_command on the node's. Its own binary: it replaces the allocation
// functions to count them. The sending half, dds_write, allocates inside Cyclone 0.10 (it
// serialises into a buffer of its own per sample); README "Not yet here" gives the count.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>

#include "allocation_counter.h"
#include "dds_test_peers.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/transport/dds_node_endpoint.h"

namespace rpsd::transport {
namespace {

constexpr std::uint32_t kTest = 71, kSite = 1;
constexpr int kWarmUp = 500, kCounted = 2000;

class DdsReceivePath : public ::testing::Test {
 protected:
  DdsReceivePath()
      : coordinator_(testing::loopback()),
        node_side_(testing::loopback()),
        link_(coordinator_, testing::link_config(kTest, kSite, 2, 2.0)),
        node_(node_side_, testing::node_config(kTest, kSite)) {}

  void SetUp() override { ASSERT_TRUE(testing::connect(link_, node_, kTest, kSite)); }

  // Answers commands until `stop`; counts, when asked, the allocations of its take_command calls.
  void answer(const std::atomic<bool>& stop, bool count_takes) {
    CommandSample c;
    while (!stop) {
      if (!node_.wait_for_command_until(realtime::monotonic_now_ns() + 20'000'000)) continue;
      for (;;) {
        if (count_takes && answered_ >= kWarmUp) rpsd::testing::begin_counting_allocations();
        const bool took = node_.take_command(c);
        if (count_takes && answered_ >= kWarmUp) take_allocations_ += rpsd::testing::end_counting_allocations().total();
        if (!took) break;
        FeedbackSample f;
        f.test_id = kTest;
        f.site_id = kSite;
        f.run_id = c.run_id;
        f.step = c.step;
        f.channels = 2;
        f.displacement_m[0] = c.displacement_m[0];
        node_.publish(f);
        ++answered_;
      }
    }
  }

  // One lock-step exchange; returns the allocations of the receive when `count_receive`.
  long exchange(int step, bool count_receive) {
    CommandSample c;
    c.step = step;
    c.channels = 2;
    c.displacement_m[0] = 1e-5 * step;
    EXPECT_EQ(link_.send(c), LinkStatus::kOk);
    FeedbackSample f;
    if (count_receive) rpsd::testing::begin_counting_allocations();
    const LinkStatus status = link_.receive(f);
    const long allocations = count_receive ? rpsd::testing::end_counting_allocations().total() : 0;
    EXPECT_EQ(status, LinkStatus::kOk) << "step " << step;
    EXPECT_EQ(f.step, step);
    return allocations;
  }

  DdsParticipant coordinator_, node_side_;
  DdsLink link_;
  DdsNodeEndpoint node_;
  std::atomic<long> answered_{0};
  long take_allocations_ = 0;  // written by the answering thread, read after its join
};

TEST_F(DdsReceivePath, TheCoordinatorsReceiveAllocatesNothing) {
  std::atomic<bool> stop{false};
  std::thread node([&] { answer(stop, false); });
  long allocations = 0;
  for (int step = 0; step < kWarmUp + kCounted; ++step) allocations += exchange(step, step >= kWarmUp);
  stop = true;
  node.join();
  EXPECT_EQ(allocations, 0);
  // The waitset was slept on (the node answers on another thread), not only polled.
  EXPECT_GT(link_.counters().waits, kCounted / 2);
}

TEST_F(DdsReceivePath, TheNodesTakeAllocatesNothing) {
  std::atomic<bool> stop{false};
  std::thread node([&] { answer(stop, true); });
  for (int step = 0; step < kWarmUp + kCounted; ++step) exchange(step, false);
  stop = true;
  node.join();
  EXPECT_EQ(answered_, kWarmUp + kCounted);
  EXPECT_EQ(take_allocations_, 0);
}

}  // namespace
}  // namespace rpsd::transport
