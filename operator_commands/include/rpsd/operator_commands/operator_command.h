// An operator's command to a running test (issue 31): stop it in order, abort it (the nodes
// hold at once), or, in lock-step, hold it and resume it from the same step. Sent over the
// test's DDS partition by `rpsd stop` or `rpsd monitor`; the coordinator answers each with a
// reply saying whether it acted. The rig's hardware emergency stop stays the primary stop.
#pragma once

#include <array>
#include <cstdint>

namespace rpsd::operator_commands {

enum class OperatorAction : std::uint8_t { kStop, kAbort, kHold, kResume };

struct OperatorCommand {
  std::uint32_t test_id = 0;
  std::uint64_t run_id = 0;  // 0: whatever run of test_id is under way
  OperatorAction action = OperatorAction::kStop;
  std::array<char, 64> sender{};  // who sent it, for the log: "monitor@host (browser 198.18.0.5)"
  std::int64_t sent_unix_ns = 0;
  std::uint64_t sequence = 0;  // per sender: the reply names it
};

enum class ReplyStatus : std::uint8_t { kDone, kRefused };

struct OperatorReply {
  std::uint32_t test_id = 0;
  std::uint64_t run_id = 0;
  std::array<char, 64> sender{};  // the command's
  std::uint64_t sequence = 0;     // the command's
  ReplyStatus status = ReplyStatus::kRefused;
  std::array<char, 160> text{};  // what was done, or why not ("hold: a real-time test cannot hold")
};

}  // namespace rpsd::operator_commands
