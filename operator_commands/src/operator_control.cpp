#include "rpsd/operator_commands/operator_control.h"

namespace rpsd::operator_commands {

void OperatorControl::request_stop(const std::string& who) {
  const std::lock_guard lock(who_mutex_);
  if (request() != OperatorRequest::kNone) return;
  requested_by_ = who;
  request_.store(static_cast<std::uint8_t>(OperatorRequest::kStop), std::memory_order_release);
}

void OperatorControl::request_abort(const std::string& who) {
  const std::lock_guard lock(who_mutex_);
  if (request() == OperatorRequest::kAbort) return;
  requested_by_ = who;
  request_.store(static_cast<std::uint8_t>(OperatorRequest::kAbort), std::memory_order_release);
}

std::string OperatorControl::requested_by() const {
  const std::lock_guard lock(who_mutex_);
  return requested_by_;
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
