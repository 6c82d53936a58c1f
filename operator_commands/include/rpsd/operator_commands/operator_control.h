// How accepted operator commands reach the loop: flags the loop polls between steps (one
// atomic load each, real-time safe: no lock, allocation or I/O), set by the listener's thread.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

namespace rpsd::operator_commands {

enum class OperatorRequest : std::uint8_t { kNone, kStop, kAbort };

class OperatorControl {
 public:
  // What the loop must do after the step under way. Real-time safe.
  OperatorRequest request() const { return static_cast<OperatorRequest>(request_.load(std::memory_order_acquire)); }
  // A hold is asked (lock-step only): take no further step until it is lifted. Real-time safe.
  bool hold_requested() const { return hold_.load(std::memory_order_acquire); }

  // The listener's side. An abort replaces a stop, never the other way round.
  void request_stop();
  void request_abort();
  // False when already held (hold) or not held (resume); `who` is kept for the held interval.
  bool request_hold(const std::string& who);
  bool request_resume(const std::string& who);

  // Who asked for the hold under way and who lifted the last one. Not real-time safe (a
  // mutex): the lock-step loop asks when it enters and leaves a hold, never in real time.
  std::string held_by() const;
  std::string resumed_by() const;

 private:
  std::atomic<std::uint8_t> request_{static_cast<std::uint8_t>(OperatorRequest::kNone)};
  std::atomic<bool> hold_{false};
  mutable std::mutex who_mutex_;
  std::string held_by_, resumed_by_;
};

}  // namespace rpsd::operator_commands
