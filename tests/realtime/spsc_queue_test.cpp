// SpscQueue: capacity, FIFO order, full and empty on one thread; then a producer and a
// consumer on two threads pushing millions of records through a small ring, every record
// checked to arrive exactly once, in order, with its payload intact.
#include "rpsd/realtime/spsc_queue.h"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
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
};

// The producer pushes `count` records in place, retrying while the ring is full; the
// consumer pops them in place, retrying while it is empty, and checks each is the next in
// sequence and intact. The consumer stops when the producer has finished and the queue is
// empty, so a queue that loses records fails rather than hangs.
//
// A side that keeps finding the ring full (or empty) spins briefly, then sleeps until the
// other side has moved (a futex through std::atomic::wait): on a loaded machine the two
// threads may share one core with other processes, and spinning or yielding there only
// burns the time slice the other side needs (the test once took 120 s on a busy 2-core
// machine). Each side counts its moves and wakes the other; no clock is read.
class Progress {
 public:
  void moved() {
    count_.fetch_add(1, std::memory_order_release);
    count_.notify_one();
  }
  std::uint64_t now() const { return count_.load(std::memory_order_acquire); }
  void wait_past(std::uint64_t seen) const { count_.wait(seen, std::memory_order_acquire); }

 private:
  std::atomic<std::uint64_t> count_{0};
};

constexpr std::uint64_t kSpinsBeforeSleeping = 256;

StressResult stress(std::size_t capacity, std::uint64_t count) {
  SpscQueue<Record> q(capacity);
  StressResult result;
  Progress pushes, pops;
  std::atomic<bool> producer_done{false};
  // Called after a failed try: `other` is the side whose move would let this one go on,
  // `seen` its count read before the try.
  const auto wait = [](std::uint64_t& failures, std::uint64_t& in_a_row, const Progress& other, std::uint64_t seen) {
    ++failures;
    if (++in_a_row < kSpinsBeforeSleeping) return;
    other.wait_past(seen);
    in_a_row = 0;
  };
  std::thread consumer([&] {
    std::uint64_t expected = 0, in_a_row = 0;
    const auto check = [&](const Record& r) {
      if (!intact(r, expected) && result.bad++ == 0) {
        result.first_bad_at = expected;
        result.first_bad_sequence = r.sequence;
      }
      ++expected;
    };
    while (expected < count) {
      const std::uint64_t pushed_before = pushes.now();
      if (q.try_pop_with(check)) {
        in_a_row = 0;
        pops.moved();
        continue;
      }
      if (producer_done.load(std::memory_order_acquire)) {
        if (!q.try_pop_with(check)) break;  // every push is visible now: the rest were lost
        pops.moved();
        continue;
      }
      wait(result.empty, in_a_row, pushes, pushed_before);
    }
    result.popped = expected;
  });
  std::thread producer([&] {
    std::uint64_t next = 0, in_a_row = 0;
    while (next < count) {
      const std::uint64_t popped_before = pops.now();
      if (q.try_push_with([&](Record& slot) { fill(slot, next); })) {
        ++next;
        in_a_row = 0;
        pushes.moved();
      } else {
        wait(result.full, in_a_row, pops, popped_before);
      }
    }
    result.pushed = next;
    producer_done.store(true, std::memory_order_release);
    pushes.moved();  // wakes a consumer asleep on an empty ring, to see that it is done
  });
  producer.join();
  consumer.join();
  Record left;
  EXPECT_FALSE(q.try_pop(left)) << "a record beyond the last one pushed";
  return result;
}

void expect_every_record_once_in_order(std::size_t capacity, std::uint64_t count) {
  const StressResult r = stress(capacity, count);
  EXPECT_EQ(r.pushed, count);
  EXPECT_EQ(r.popped, count);
  EXPECT_EQ(r.bad, 0u) << "first bad record: expected sequence " << r.first_bad_at << ", got " << r.first_bad_sequence;
  testing::Test::RecordProperty("full", std::to_string(r.full));
  testing::Test::RecordProperty("empty", std::to_string(r.empty));
  std::printf("capacity %zu: %llu records, %llu pushes found it full, %llu pops found it empty\n", capacity,
              static_cast<unsigned long long>(count), static_cast<unsigned long long>(r.full),
              static_cast<unsigned long long>(r.empty));
}

// Three slots hand over every third record, so a million records are a third of a million
// wrap-arounds with the other thread, and take a few seconds even when both threads share a
// loaded core.
TEST(SpscQueue, TwoThreadsPassOneMillionRecordsThroughThreeSlotsOnceInOrderIntact) {
  expect_every_record_once_in_order(3, 1'000'000);
}

TEST(SpscQueue, TwoThreadsPassFiveMillionRecordsThroughSixtyFourSlotsOnceInOrderIntact) {
  expect_every_record_once_in_order(64, 5'000'000);
}

}  // namespace
}  // namespace rpsd::realtime
