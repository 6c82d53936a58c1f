#include "rpsd/operator_commands/operator_command_handler.h"

#include <cstdio>
#include <ctime>

#include "rpsd/operator_commands/operator_command_sender.h"

namespace rpsd::operator_commands {

std::string sender_text(const std::array<char, 64>& sender) {
  std::size_t n = 0;
  while (n < sender.size() && sender[n] != '\0') ++n;
  return std::string(sender.data(), n);
}

OperatorCommandHandler::OperatorCommandHandler(OperatorHandlerOptions options, OperatorControl& control)
    : options_(std::move(options)), control_(control) {}

OperatorReply OperatorCommandHandler::decide(const OperatorCommand& command) {
  OperatorReply reply;
  reply.test_id = options_.test_id;
  reply.run_id = options_.run_id;
  reply.sender = command.sender;
  reply.sequence = command.sequence;
  const char* name = operator_action_name(command.action);
  const auto answer = [&](ReplyStatus status, const std::string& text) {
    reply.status = status;
    copy_text(std::string(name) + ": " + text, reply.text);
    return reply;
  };
  if (!options_.accepting) return answer(ReplyStatus::kRefused, options_.not_accepting_reason);
  const OperatorRequest request = control_.request();
  switch (command.action) {
    case OperatorAction::kAbort:
      control_.request_abort();
      return answer(ReplyStatus::kDone, "the coordinator stops commanding and every node holds at once");
    case OperatorAction::kStop:
      if (request == OperatorRequest::kAbort) return answer(ReplyStatus::kRefused, "the test is already aborted");
      control_.request_stop();
      return answer(ReplyStatus::kDone, options_.stop_effect);
    case OperatorAction::kHold:
    case OperatorAction::kResume:
      if (options_.real_time) {
        return answer(ReplyStatus::kRefused, "a real-time test cannot hold (only a lock-step test can)");
      }
      if (request != OperatorRequest::kNone) return answer(ReplyStatus::kRefused, "the test is already stopping");
      if (command.action == OperatorAction::kHold) {
        if (!control_.request_hold(sender_text(command.sender)))
          return answer(ReplyStatus::kRefused, "the test is already held");
        return answer(ReplyStatus::kDone, "the test holds after the step under way; the actuators hold their command");
      }
      if (!control_.request_resume(sender_text(command.sender)))
        return answer(ReplyStatus::kRefused, "the test is not held");
      return answer(ReplyStatus::kDone, "the test carries on from the step where it held");
  }
  return answer(ReplyStatus::kRefused, "unknown action");
}

std::optional<OperatorReply> OperatorCommandHandler::handle(const OperatorCommand& command,
                                                            std::int64_t received_unix_ns) {
  const std::lock_guard lock(mutex_);
  const std::string who = sender_text(command.sender);
  const bool other_run = command.test_id != options_.test_id || (command.run_id != 0 && command.run_id != options_.run_id);
  const auto previous = last_reply_.find(who);
  if (!other_run && previous != last_reply_.end()) {
    if (command.sequence == previous->second.sequence) return previous->second;  // a repeat: same answer
    if (command.sequence < previous->second.sequence) return std::nullopt;       // older than answered
  }
  OperatorCommandEvent event;
  event.action = command.action;
  event.sender = who;
  event.sequence = command.sequence;
  event.sent_unix_ns = command.sent_unix_ns;
  event.received_unix_ns = received_unix_ns;
  std::optional<OperatorReply> reply;
  if (other_run) {
    event.reply = "ignored: meant for test " + std::to_string(command.test_id) + " run " +
                  std::to_string(command.run_id) + ", not this run";
  } else {
    reply = decide(command);
    event.status = reply->status;
    event.reply.assign(reply->text.data(), std::char_traits<char>::length(reply->text.data()));
    last_reply_[who] = *reply;
  }
  log_.push_back(event);
  if (options_.print_to_stderr) {
    const std::time_t seconds = static_cast<std::time_t>(received_unix_ns / 1'000'000'000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char when[32];
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
    std::fprintf(stderr, "\noperator command %s from \"%s\" at %s: %s (%s)\n", operator_action_name(command.action),
                 who.c_str(), when, reply && reply->status == ReplyStatus::kDone ? "done" : "refused",
                 event.reply.c_str());
  }
  if (options_.on_command) options_.on_command(event);
  return reply;
}

std::vector<OperatorCommandEvent> OperatorCommandHandler::log() const {
  const std::lock_guard lock(mutex_);
  return log_;
}

}  // namespace rpsd::operator_commands
