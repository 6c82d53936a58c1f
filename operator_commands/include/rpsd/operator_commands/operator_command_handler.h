// The coordinator's decision on each operator command, apart from DDS: accept it (set the
// loop's flag) or refuse it, answer it, and log it with who sent it and when. A command repeated
// under the same sequence number (the sender repeats until answered) gets the same reply and
// no second action. Not real-time safe: runs on the listener's thread.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "rpsd/operator_commands/operator_command.h"
#include "rpsd/operator_commands/operator_control.h"

namespace rpsd::operator_commands {

// One command as the coordinator heard and answered it (summary.json's operator_commands).
struct OperatorCommandEvent {
  OperatorAction action = OperatorAction::kStop;
  std::string sender;
  std::uint64_t sequence = 0;
  std::int64_t sent_unix_ns = 0;      // as the sender's clock says
  std::int64_t received_unix_ns = 0;  // as this host's clock says
  ReplyStatus status = ReplyStatus::kRefused;
  std::string reply;  // what was done, or why not
};

struct OperatorHandlerOptions {
  std::uint32_t test_id = 1;
  std::uint64_t run_id = 0;
  // Whether this run acts on operator commands (DDS Security on, or the scenario enables
  // them); when not, `not_accepting_reason` is every reply.
  bool accepting = false;
  std::string not_accepting_reason;
  bool real_time = false;  // hold and resume are refused
  // Whether a stop returns the actuators to their start positions, said in the reply.
  std::string stop_effect = "the test ends in order after the step under way; the actuators hold";
  // Called for every command logged, on the listener's thread: the hook for telemetry's
  // events (the lead wires publish_event here). Must not throw.
  std::function<void(const OperatorCommandEvent&)> on_command;
  bool print_to_stderr = true;
};

class OperatorCommandHandler {
 public:
  OperatorCommandHandler(OperatorHandlerOptions options, OperatorControl& control);

  // The reply to `command` received at `received_unix_ns`; nullopt when the command is not
  // for this run (another test or run id: logged only) or repeats one older than the last
  // answered from its sender.
  std::optional<OperatorReply> handle(const OperatorCommand& command, std::int64_t received_unix_ns);

  // Every command logged so far, in the order received.
  std::vector<OperatorCommandEvent> log() const;

 private:
  OperatorReply decide(const OperatorCommand& command);

  OperatorHandlerOptions options_;
  OperatorControl& control_;
  mutable std::mutex mutex_;
  std::vector<OperatorCommandEvent> log_;
  std::map<std::string, OperatorReply> last_reply_;  // per sender
};

// The sender's name from its fixed-size field (up to the first NUL).
std::string sender_text(const std::array<char, 64>& sender);
// Copies text into a fixed-size field, truncated, NUL-terminated.
template <std::size_t N>
void copy_text(const std::string& text, std::array<char, N>& field) {
  field.fill('\0');
  text.copy(field.data(), N - 1);
}

}  // namespace rpsd::operator_commands
