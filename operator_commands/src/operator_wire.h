// OperatorCommand / OperatorReply to and from their generated wire types, field by field.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "rpsd/operator_commands/operator_command.h"
#include "rpsd_operator.h"

namespace rpsd::operator_commands {

// A command's send time and a sequence's start: the wall clock, which both hosts share.
inline std::int64_t unix_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

inline void to_wire(const OperatorCommand& c, rpsd_operator_Command& w) {
  w.test_id = c.test_id;
  w.run_id = c.run_id;
  w.action = static_cast<std::uint8_t>(c.action);
  std::copy(c.sender.begin(), c.sender.end(), w.sender);
  w.sender[sizeof w.sender - 1] = '\0';
  w.sent_unix_ns = c.sent_unix_ns;
  w.sequence_number = c.sequence;
}

// False when the action is not one rpsd knows.
inline bool from_wire(const rpsd_operator_Command& w, OperatorCommand& c) {
  if (w.action > static_cast<std::uint8_t>(OperatorAction::kResume)) return false;
  c.test_id = w.test_id;
  c.run_id = w.run_id;
  c.action = static_cast<OperatorAction>(w.action);
  std::copy(std::begin(w.sender), std::end(w.sender), c.sender.begin());
  c.sender.back() = '\0';
  c.sent_unix_ns = w.sent_unix_ns;
  c.sequence = w.sequence_number;
  return true;
}

inline void to_wire(const OperatorReply& r, rpsd_operator_Reply& w) {
  w.test_id = r.test_id;
  w.run_id = r.run_id;
  std::copy(r.sender.begin(), r.sender.end(), w.sender);
  w.sender[sizeof w.sender - 1] = '\0';
  w.sequence_number = r.sequence;
  w.status = static_cast<std::uint8_t>(r.status);
  std::copy(r.text.begin(), r.text.end(), w.text);
  w.text[sizeof w.text - 1] = '\0';
}

inline void from_wire(const rpsd_operator_Reply& w, OperatorReply& r) {
  r.test_id = w.test_id;
  r.run_id = w.run_id;
  std::copy(std::begin(w.sender), std::end(w.sender), r.sender.begin());
  r.sender.back() = '\0';
  r.sequence = w.sequence_number;
  r.status = w.status == 0 ? ReplyStatus::kDone : ReplyStatus::kRefused;
  std::copy(std::begin(w.text), std::end(w.text), r.text.begin());
  r.text.back() = '\0';
}

}  // namespace rpsd::operator_commands
