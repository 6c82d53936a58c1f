// The live stream: a slow browser loses its own oldest messages, counted, and nobody else's;
// a browser that joins gets the recent past of the current run; the number of streams is
// bounded; closing the hub ends every wait.
#include "rpsd/monitor/stream_hub.h"

#include <gtest/gtest.h>

#include <thread>

namespace rpsd::monitor {
namespace {

using namespace std::chrono_literals;

// GCC 12 warns falsely (-Wrestrict) on "literal" + std::to_string.
std::string named(const char* prefix, int i) {
  std::string s(prefix);
  s.append(std::to_string(i));
  return s;
}

std::vector<std::string> drain(StreamHub& hub, StreamHub::ClientId id, std::uint64_t& dropped) {
  std::vector<StreamHub::Message> got;
  EXPECT_TRUE(hub.next(id, got, 0ms, dropped));
  std::vector<std::string> out;
  for (const auto& m : got) out.push_back(*m);
  return out;
}

TEST(StreamHub, ASlowBrowserDropsItsOldestAndCountsThemWhileAnotherGetsAll) {
  StreamHubOptions o;
  o.client_queue_messages = 4;
  StreamHub hub(o);
  const auto slow = hub.join(), fast = hub.join();
  ASSERT_TRUE(slow && fast);
  std::uint64_t dropped = 0;
  for (int i = 0; i < 10; ++i) {
    hub.publish_transient(named("m", i));
    EXPECT_EQ(drain(hub, *fast, dropped), std::vector<std::string>{named("m", i)});
    EXPECT_EQ(dropped, 0u);
  }
  EXPECT_EQ(drain(hub, *slow, dropped), (std::vector<std::string>{"m6", "m7", "m8", "m9"}));
  EXPECT_EQ(dropped, 6u);
  EXPECT_EQ(hub.dropped_total(), 6u);
}

TEST(StreamHub, AJoiningBrowserGetsTheLastSecondsOfTheCurrentRunAndTheEvents) {
  StreamHubOptions o;
  o.recent_past_s = 10.0;
  StreamHub hub(o);
  hub.publish_batch("old run", 1, 50.0);
  hub.publish_event("event A");
  for (int t = 0; t <= 30; t += 5) hub.publish_batch(named("run2 t", t), 2, t);
  const auto id = hub.join();
  ASSERT_TRUE(id);
  std::uint64_t dropped = 0;
  EXPECT_EQ(drain(hub, *id, dropped), (std::vector<std::string>{"event A", "run2 t20", "run2 t25", "run2 t30"}));
}

TEST(StreamHub, StreamsAreBoundedAndALeaverFreesItsPlace) {
  StreamHubOptions o;
  o.max_clients = 2;
  StreamHub hub(o);
  const auto a = hub.join(), b = hub.join();
  ASSERT_TRUE(a && b);
  EXPECT_FALSE(hub.join());
  hub.leave(*a);
  EXPECT_TRUE(hub.join());
  EXPECT_EQ(hub.clients(), 2u);
}

TEST(StreamHub, CloseEndsAWaitingStream) {
  StreamHub hub;
  const auto id = hub.join();
  ASSERT_TRUE(id);
  bool result = true;
  std::thread waiter([&] {
    std::vector<StreamHub::Message> got;
    std::uint64_t dropped = 0;
    result = hub.next(*id, got, 60s, dropped);  // a hang guard, not a measured time
  });
  std::this_thread::sleep_for(20ms);
  hub.close();
  waiter.join();
  EXPECT_FALSE(result);
  EXPECT_FALSE(hub.join());
}

}  // namespace
}  // namespace rpsd::monitor
