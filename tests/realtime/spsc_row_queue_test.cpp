// SpscRowQueue: rows of a size chosen at construction, back to back in a cache-line-aligned,
// zeroed ring; capacity, FIFO order, full and empty on one thread; then a producer and a
// consumer on two threads passing a million rows that straddle cache lines through a small
// ring, each row checked to arrive once, in order, every word intact.
#include "rpsd/realtime/spsc_row_queue.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace rpsd::realtime {
namespace {

constexpr std::size_t kWords = 5;  // 40-byte rows: most straddle two cache lines
constexpr std::size_t kRowBytes = kWords * sizeof(std::uint64_t);

void fill(std::byte* row, std::uint64_t sequence) {
  for (std::size_t w = 0; w < kWords; ++w) {
    const std::uint64_t v = sequence * 0x9e3779b97f4a7c15ULL + w;
    std::memcpy(row + w * sizeof v, &v, sizeof v);
  }
}

bool intact(const std::byte* row, std::uint64_t sequence) {
  for (std::size_t w = 0; w < kWords; ++w) {
    std::uint64_t v = 0;
    std::memcpy(&v, row + w * sizeof v, sizeof v);
    if (v != sequence * 0x9e3779b97f4a7c15ULL + w) return false;
  }
  return true;
}

TEST(SpscRowQueue, HoldsExactlyItsCapacityInFifoOrderAndReportsFullAndEmpty) {
  SpscRowQueue q(3, kRowBytes);
  EXPECT_EQ(q.row_bytes(), kRowBytes);
  EXPECT_FALSE(q.try_pop_with([](const std::byte*) { ADD_FAILURE() << "read from an empty queue"; }));
  for (std::uint64_t n = 0; n < 3; ++n) EXPECT_TRUE(q.try_push_with([&](std::byte* row) { fill(row, n); }));
  EXPECT_FALSE(q.try_push_with([](std::byte*) { ADD_FAILURE() << "wrote to a full queue"; }));
  for (std::uint64_t n = 0; n < 3; ++n) {
    EXPECT_TRUE(q.try_pop_with([&](const std::byte* row) { EXPECT_TRUE(intact(row, n)) << n; }));
  }
  EXPECT_FALSE(q.try_pop_with([](const std::byte*) { ADD_FAILURE() << "read from an empty queue"; }));
}

// The rows lie back to back from a cache-line boundary, in a ring of capacity + 1 rows
// rounded up to whole lines, zeroed before the first push.
TEST(SpscRowQueue, RowsLieBackToBackInAZeroedCacheLineAlignedRing) {
  SpscRowQueue q(4, kRowBytes);
  EXPECT_EQ(q.ring_bytes(), (5 * kRowBytes + 63) / 64 * 64);
  const std::byte* previous = nullptr;
  for (int n = 0; n < 5; ++n) {
    ASSERT_TRUE(q.try_push_with([&](std::byte* row) {
      if (n == 0) {
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(row) % 64, 0u);
      }
      if (previous) {
        EXPECT_EQ(row - previous, static_cast<std::ptrdiff_t>(kRowBytes));
      }
      for (std::size_t b = 0; b < kRowBytes; ++b) EXPECT_EQ(row[b], std::byte{0}) << "row " << n << " byte " << b;
      previous = row;
    }));
    ASSERT_TRUE(q.try_pop_with([](const std::byte*) {}));
  }
  EXPECT_THROW(SpscRowQueue(4, 0), std::invalid_argument);
}

// Three rows of 40 bytes: a third of a million wrap-arounds with the other thread.
TEST(SpscRowQueue, TwoThreadsPassOneMillionRowsThroughThreeRowsOnceInOrderIntact) {
  constexpr std::uint64_t kCount = 1'000'000;
  SpscRowQueue q(3, kRowBytes);
  std::uint64_t popped = 0, bad = 0;
  std::thread consumer([&] {
    while (popped < kCount) {
      if (!q.try_pop_with([&](const std::byte* row) { bad += intact(row, popped) ? 0 : 1; })) {
        std::this_thread::yield();
        continue;
      }
      ++popped;
    }
  });
  for (std::uint64_t n = 0; n < kCount;) {
    if (q.try_push_with([&](std::byte* row) { fill(row, n); })) {
      ++n;
    } else {
      std::this_thread::yield();
    }
  }
  consumer.join();
  EXPECT_EQ(popped, kCount);
  EXPECT_EQ(bad, 0u);
  EXPECT_FALSE(q.try_pop_with([](const std::byte*) {})) << "a row beyond the last one pushed";
}

}  // namespace
}  // namespace rpsd::realtime
