// SpscQueue: capacity, FIFO order, full and empty on one thread; then a producer and a
// consumer on two threads pushing millions of records through a small ring, every record
// checked to arrive exactly once, in order, with its payload intact.
#include "rpsd/realtime/spsc_queue.h"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>

namespace rpsd::realtime {
namespace {

TEST(SpscQueue, HoldsExactlyItsCapacityInFifoOrderAndReportsFullAndEmpty) {
  SpscQueue<int> q(3);
  int out = -1;
  EXPECT_FALSE(q.try_pop(out));  // empty at the start
  EXPECT_EQ(out, -1);
  EXPECT_TRUE(q.try_push(10));
  EXPECT_TRUE(q.try_push(11));
  EXPECT_TRUE(q.try_push(12));
  EXPECT_FALSE(q.try_push(13));  // full at three
  ASSERT_TRUE(q.try_pop(out));
  EXPECT_EQ(out, 10);
  EXPECT_TRUE(q.try_push(13));  // one slot free again
  EXPECT_FALSE(q.try_push(14));
  for (int expected : {11, 12, 13}) {
    ASSERT_TRUE(q.try_pop(out));
    EXPECT_EQ(out, expected);
  }
  EXPECT_FALSE(q.try_pop(out));  // empty again
  EXPECT_EQ(out, 13);
}

TEST(SpscQueue, ACapacityOfOneAlternatesFullAndEmpty) {
  SpscQueue<int> q(1);
  int out = 0;
  for (int i = 0; i < 10; ++i) {
    EXPECT_TRUE(q.try_push(i));
    EXPECT_FALSE(q.try_push(-1));
    ASSERT_TRUE(q.try_pop(out));
    EXPECT_EQ(out, i);
    EXPECT_FALSE(q.try_pop(out));
  }
}

TEST(SpscQueue, StaysFifoAcrossManyWrapsOfTheRing) {
  // Batches of 1..5 pushes and 1..5 pops through a ring of 5, so the indices wrap at every
  // offset; the queue's contents are always the next values in order, and the number it
  // holds is checked against the capacity at every push.
  SpscQueue<int> q(5);
  int pushed = 0, popped = 0;
  for (int round = 0; round < 1000; ++round) {
    const int pushes = 1 + round % 5, pops = 1 + (round * 7 + 3) % 5;
    for (int i = 0; i < pushes; ++i) {
      const bool room = pushed - popped < 5;
      EXPECT_EQ(q.try_push(pushed), room) << "round " << round;
      if (room) ++pushed;
    }
    for (int i = 0; i < pops; ++i) {
      int out = -1;
      const bool some = popped < pushed;
      ASSERT_EQ(q.try_pop(out), some) << "round " << round;
      if (some) {
        EXPECT_EQ(out, popped++);
      }
    }
  }
  EXPECT_GT(popped, 2000);
}

TEST(SpscQueue, WritesAndReadsInPlaceAndCallsNeitherWhenFullOrEmpty) {
  SpscQueue<std::array<int, 4>> q(2);
  int writes = 0, reads = 0;
  const auto write = [&](std::array<int, 4>& slot) {
    ++writes;
    slot = {writes, writes, writes, writes};
  };
  const auto read = [&](const std::array<int, 4>& slot) {
    ++reads;
    EXPECT_EQ(slot, (std::array<int, 4>{reads, reads, reads, reads}));
  };
  EXPECT_FALSE(q.try_pop_with(read));
  EXPECT_TRUE(q.try_push_with(write));
  EXPECT_TRUE(q.try_push_with(write));
  EXPECT_FALSE(q.try_push_with(write));
  EXPECT_EQ(writes, 2);
  EXPECT_TRUE(q.try_pop_with(read));
  EXPECT_TRUE(q.try_pop_with(read));
  EXPECT_FALSE(q.try_pop_with(read));
  EXPECT_EQ(reads, 2);
}

// A record whose payload is a function of its sequence number, with a checksum of both, so
// that a slot read before it was written, while it is being overwritten, or twice shows.
constexpr std::size_t kPayloadWords = 14;  // two cache lines with the sequence and checksum

struct Record {
  std::uint64_t sequence = 0;
  std::array<std::uint64_t, kPayloadWords> payload{};
  std::uint64_t checksum = 0;
};

// Every 32nd record is written (and read) with a yield halfway, so that even when the two
// threads share one core (a loaded machine) the other side runs while a slot is half done.
constexpr std::uint64_t kPauseEvery = 32;
constexpr std::size_t kHalf = kPayloadWords / 2;

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t checksum(const Record& r) {
  std::uint64_t sum = mix(r.sequence);
  for (std::uint64_t p : r.payload) sum = mix(sum ^ p);
  return sum;
}

std::uint64_t payload_word(std::uint64_t sequence, std::size_t i) { return mix(sequence * kPayloadWords + i); }

void fill(Record& r, std::uint64_t sequence) {
  r.sequence = sequence;
  for (std::size_t i = 0; i < kHalf; ++i) r.payload[i] = payload_word(sequence, i);
  if (sequence % kPauseEvery == 0) std::this_thread::yield();
  for (std::size_t i = kHalf; i < r.payload.size(); ++i) r.payload[i] = payload_word(sequence, i);
  r.checksum = checksum(r);
}

bool intact(const Record& r, std::uint64_t expected_sequence) {
  bool ok = r.sequence == expected_sequence;
  for (std::size_t i = 0; i < kHalf; ++i) ok = ok && r.payload[i] == payload_word(expected_sequence, i);
  if (expected_sequence % kPauseEvery == kPauseEvery / 2) std::this_thread::yield();
  for (std::size_t i = kHalf; i < r.payload.size(); ++i) ok = ok && r.payload[i] == payload_word(expected_sequence, i);
  return ok && r.checksum == checksum(r);
}

struct StressResult {
  std::uint64_t pushed = 0, popped = 0, bad = 0;
  std::uint64_t first_bad_at = 0, first_bad_sequence = 0;
  std::uint64_t full = 0, empty = 0;  // failed pushes and pops
  bool timed_out = false;
};

// The producer pushes `count` records in place, retrying while the ring is full; the
// consumer pops them in place, retrying while it is empty, and checks each is the next in
// sequence and intact. The consumer stops when the producer has finished and the queue is
// empty, and both give up after a deadline, so a queue that loses records fails rather
// than hangs.
StressResult stress(std::size_t capacity, std::uint64_t count) {
  SpscQueue<Record> q(capacity);
  StressResult result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::atomic<bool> give_up{false}, producer_done{false};
  const auto wait = [&](std::uint64_t& failures) {
    ++failures;
    if (failures % 64 == 0) std::this_thread::yield();  // the other thread may share this core
    if (failures % 4096 == 0 && std::chrono::steady_clock::now() > deadline) give_up = true;
  };
  std::thread consumer([&] {
    std::uint64_t expected = 0;
    const auto check = [&](const Record& r) {
      if (!intact(r, expected) && result.bad++ == 0) {
        result.first_bad_at = expected;
        result.first_bad_sequence = r.sequence;
      }
      ++expected;
    };
    while (expected < count && !give_up) {
      if (q.try_pop_with(check)) continue;
      if (producer_done.load(std::memory_order_acquire)) {
        if (!q.try_pop_with(check)) break;  // every push is visible now: the rest were lost
        continue;
      }
      wait(result.empty);
    }
    result.popped = expected;
  });
  std::thread producer([&] {
    std::uint64_t next = 0;
    while (next < count && !give_up) {
      if (q.try_push_with([&](Record& slot) { fill(slot, next); })) {
        ++next;
      } else {
        wait(result.full);
      }
    }
    result.pushed = next;
    producer_done.store(true, std::memory_order_release);
  });
  producer.join();
  consumer.join();
  result.timed_out = give_up;
  Record left;
  if (!result.timed_out) {
    EXPECT_FALSE(q.try_pop(left)) << "a record beyond the last one pushed";
  }
  return result;
}

void expect_every_record_once_in_order(std::size_t capacity, std::uint64_t count) {
  const StressResult r = stress(capacity, count);
  EXPECT_FALSE(r.timed_out) << "pushed " << r.pushed << ", popped " << r.popped;
  EXPECT_EQ(r.pushed, count);
  EXPECT_EQ(r.popped, count);
  EXPECT_EQ(r.bad, 0u) << "first bad record: expected sequence " << r.first_bad_at << ", got " << r.first_bad_sequence;
  testing::Test::RecordProperty("full", std::to_string(r.full));
  testing::Test::RecordProperty("empty", std::to_string(r.empty));
  std::printf("capacity %zu: %llu records, %llu pushes found it full, %llu pops found it empty\n", capacity,
              static_cast<unsigned long long>(count), static_cast<unsigned long long>(r.full),
              static_cast<unsigned long long>(r.empty));
}

constexpr std::uint64_t kStressRecords = 5'000'000;

TEST(SpscQueue, TwoThreadsPassFiveMillionRecordsThroughThreeSlotsOnceInOrderIntact) {
  expect_every_record_once_in_order(3, kStressRecords);
}

TEST(SpscQueue, TwoThreadsPassFiveMillionRecordsThroughSixtyFourSlotsOnceInOrderIntact) {
  expect_every_record_once_in_order(64, kStressRecords);
}

}  // namespace
}  // namespace rpsd::realtime
