// The live sink: the test's operator partition (operator_commands::OperatorCommandSender).
// The coordinator logs the sender's name ("monitor@rig-pc"); the monitor logs which browser
// asked (MonitorServer's log), so that every command can be traced to a person's screen.
#pragma once

#include <string>

#include "rpsd/monitor/command_sink.h"
#include "rpsd/operator_commands/operator_command_sender.h"

namespace rpsd::monitor {

class DdsCommandSink final : public CommandSink {
 public:
  // Joins the domain and the operator partition; throws as OperatorCommandSender does.
  DdsCommandSink(const operator_commands::OperatorLinkConfig& config, std::string sender_name, double reply_timeout_s)
      : sender_(config, std::move(sender_name)), reply_timeout_s_(reply_timeout_s) {}

  std::optional<operator_commands::OperatorReply> send(operator_commands::OperatorAction action,
                                                       const std::string& /*origin: logged by the server*/) override {
    return sender_.send(action, reply_timeout_s_);
  }

 private:
  operator_commands::OperatorCommandSender sender_;
  double reply_timeout_s_;
};

}  // namespace rpsd::monitor
