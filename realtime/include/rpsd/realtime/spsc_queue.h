// Bounded single-producer single-consumer queue: the real-time thread try-pushes, a writer
// thread pops. No locks, no allocation after construction. Each side keeps its own copy of
// the other side's index and reads the shared one only when its copy says full (or empty),
// so a push or pop does not pull the other thread's cache line every time; records are
// written and read in place.
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

namespace rpsd::realtime {

template <typename T>
class SpscQueue {
 public:
  // Not real-time safe (allocates the ring).
  explicit SpscQueue(std::size_t capacity) : slots_(capacity + 1) {}

  // Producer side: write(slot) fills the next free slot in place. False when full (the
  // caller counts the drop). Real-time safe when write is.
  template <typename Write>
  bool try_push_with(Write&& write) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t next = following(tail);
    if (next == cached_head_) {
      cached_head_ = head_.load(std::memory_order_acquire);
      if (next == cached_head_) return false;
    }
    write(slots_[tail]);
    tail_.store(next, std::memory_order_release);
    return true;
  }

  // Producer side, by copy. Real-time safe.
  bool try_push(const T& value) {
    return try_push_with([&](T& slot) { slot = value; });
  }

  // Consumer side: read(slot) sees the oldest element in place. False when empty.
  template <typename Read>
  bool try_pop_with(Read&& read) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == cached_tail_) {
      cached_tail_ = tail_.load(std::memory_order_acquire);
      if (head == cached_tail_) return false;
    }
    read(static_cast<const T&>(slots_[head]));
    head_.store(following(head), std::memory_order_release);
    return true;
  }

  // Consumer side, by copy.
  bool try_pop(T& out) {
    return try_pop_with([&](const T& slot) { out = slot; });
  }

 private:
  std::size_t following(std::size_t index) const { return index + 1 == slots_.size() ? 0 : index + 1; }

  std::vector<T> slots_;
  // The consumer's line: its index and its copy of the producer's.
  alignas(64) std::atomic<std::size_t> head_{0};
  std::size_t cached_tail_ = 0;
  // The producer's line.
  alignas(64) std::atomic<std::size_t> tail_{0};
  std::size_t cached_head_ = 0;
};

}  // namespace rpsd::realtime
