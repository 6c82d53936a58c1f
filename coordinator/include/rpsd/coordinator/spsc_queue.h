// Bounded single-producer single-consumer queue: the real-time thread try-pushes, a writer
// thread pops. No locks, no allocation after construction.
#pragma once

#include <atomic>
#include <cstddef>
#include <new>
#include <optional>
#include <vector>

namespace rpsd::coordinator {

template <typename T>
class SpscQueue {
 public:
  /// Not real-time safe (allocates the ring).
  explicit SpscQueue(std::size_t capacity) : slots_(capacity + 1) {}

  /// Producer side. False when full (the caller counts the drop). Real-time safe.
  bool try_push(const T& value) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t next = (tail + 1) % slots_.size();
    if (next == head_.load(std::memory_order_acquire)) return false;
    slots_[tail] = value;
    tail_.store(next, std::memory_order_release);
    return true;
  }

  /// Consumer side.
  bool try_pop(T& out) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_.load(std::memory_order_acquire)) return false;
    out = slots_[head];
    head_.store((head + 1) % slots_.size(), std::memory_order_release);
    return true;
  }

 private:
  std::vector<T> slots_;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace rpsd::coordinator
