// Where the page's operator commands go: the test's operator partition in a run
// (dds_command_sink.h, over operator_commands::OperatorCommandSender), a fake that records
// them in the tests. The server has checked the token before it calls send.
#pragma once

#include <optional>
#include <string>

#include "rpsd/operator_commands/operator_command.h"

namespace rpsd::monitor {

class CommandSink {
 public:
  virtual ~CommandSink() = default;
  // Sends `action` for the browser at `origin` ("198.18.0.5:51234"); the coordinator's reply,
  // or nullopt when none came (no run of the test, or DDS Security let the command through to
  // no one). Called from several server threads at once. Not real-time safe.
  virtual std::optional<operator_commands::OperatorReply> send(operator_commands::OperatorAction action,
                                                               const std::string& origin) = 0;
};

}  // namespace rpsd::monitor
