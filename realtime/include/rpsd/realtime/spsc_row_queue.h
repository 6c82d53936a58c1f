// Bounded single-producer single-consumer queue of rows of bytes, their size chosen at
// construction, for a record whose packed size depends on the test (the recorder's,
// record_layout.h). Rows lie back to back in one cache-line-aligned buffer, zeroed (and so
// faulted in) when the queue is built, so a push writes only the lines its row covers and
// never faults. No locks, no allocation after construction.
#pragma once

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace rpsd::realtime {

class SpscRowQueue {
 public:
  // Not real-time safe (allocates and zeroes the ring). row_bytes > 0.
  SpscRowQueue(std::size_t capacity, std::size_t row_bytes)
      : rows_(capacity + 1), row_bytes_(row_bytes), lines_((rows_ * row_bytes_ + kLine - 1) / kLine) {
    if (row_bytes_ == 0) throw std::invalid_argument("SpscRowQueue: rows of zero bytes");
  }

  std::size_t row_bytes() const { return row_bytes_; }
  // Bytes the ring holds (capacity + 1 rows, rounded up to whole cache lines).
  std::size_t ring_bytes() const { return lines_.size() * kLine; }

  // Producer side: write(std::byte* row) fills the next free row in place. False when full
  // (the caller counts the drop). The consumer only reads a row, so the row stays as written
  // until the producer's next push: the producer may read it back until then. Real-time safe
  // when write is.
  template <typename Write>
  bool try_push_with(Write&& write) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t next = following(tail);
    if (next == cached_head_) {
      cached_head_ = head_.load(std::memory_order_acquire);
      if (next == cached_head_) return false;
    }
    write(row(tail));
    tail_.store(next, std::memory_order_release);
    return true;
  }

  // Consumer side: read(const std::byte* row) sees the oldest row in place. False when empty.
  template <typename Read>
  bool try_pop_with(Read&& read) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == cached_tail_) {
      cached_tail_ = tail_.load(std::memory_order_acquire);
      if (head == cached_tail_) return false;
    }
    read(static_cast<const std::byte*>(row(head)));
    head_.store(following(head), std::memory_order_release);
    return true;
  }

 private:
  static constexpr std::size_t kLine = 64;
  struct alignas(kLine) Line {
    std::byte bytes[kLine];
  };

  std::size_t following(std::size_t index) const { return index + 1 == rows_ ? 0 : index + 1; }
  std::byte* row(std::size_t index) { return reinterpret_cast<std::byte*>(lines_.data()) + index * row_bytes_; }

  std::size_t rows_, row_bytes_;
  std::vector<Line> lines_;
  // The consumer's line: its index and its copy of the producer's.
  alignas(64) std::atomic<std::size_t> head_{0};
  std::size_t cached_tail_ = 0;
  // The producer's line.
  alignas(64) std::atomic<std::size_t> tail_{0};
  std::size_t cached_head_ = 0;
};

}  // namespace rpsd::realtime
