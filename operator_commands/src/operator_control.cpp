#include "rpsd/operator_commands/operator_control.h"

namespace rpsd::operator_commands {

void OperatorControl::request_stop() {
  std::uint8_t none = static_cast<std::uint8_t>(OperatorRequest::kNone);
  request_.compare_exchange_strong(none, static_cast<std::uint8_t>(OperatorRequest::kStop), std::memory_order_acq_rel);
}

void OperatorControl::request_abort() {
  request_.store(static_cast<std::uint8_t>(OperatorRequest::kAbort), std::memory_order_release);
}

bool OperatorControl::request_hold(const std::string& who) {
  const std::lock_guard lock(who_mutex_);
  if (hold_.load(std::memory_order_acquire)) return false;
  held_by_ = who;
  hold_.store(true, std::memory_order_release);
  return true;
}

bool OperatorControl::request_resume(const std::string& who) {
  const std::lock_guard lock(who_mutex_);
  if (!hold_.load(std::memory_order_acquire)) return false;
  resumed_by_ = who;
  hold_.store(false, std::memory_order_release);
  return true;
}

std::string OperatorControl::held_by() const {
  const std::lock_guard lock(who_mutex_);
  return held_by_;
}

std::string OperatorControl::resumed_by() const {
  const std::lock_guard lock(who_mutex_);
  return resumed_by_;
}

}  // namespace rpsd::operator_commands
