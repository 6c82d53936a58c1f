// The coordinator's side: a DDS reader on the test's operator partition, served by a thread of
// its own (never the loop's), which decides on each command (OperatorCommandHandler), sets the
// loop's flags (OperatorControl) and writes the reply.
#pragma once

#include <memory>
#include <vector>

#include "rpsd/operator_commands/operator_command_handler.h"
#include "rpsd/operator_commands/operator_command_sender.h"
#include "rpsd/operator_commands/operator_control.h"

namespace rpsd::operator_commands {

class OperatorCommandListener {
 public:
  // Joins the domain (link.dds_config: the coordinator's own Cyclone configuration) and starts
  // the thread. Not real-time safe; throws transport::DdsError or std::runtime_error.
  OperatorCommandListener(const OperatorLinkConfig& link, OperatorHandlerOptions options, OperatorControl& control);
  // Stops the thread; commands after this get no reply.
  ~OperatorCommandListener();
  OperatorCommandListener(const OperatorCommandListener&) = delete;
  OperatorCommandListener& operator=(const OperatorCommandListener&) = delete;

  std::vector<OperatorCommandEvent> log() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Whether a Cyclone configuration turns DDS Security on: the file named, or else what
// CYCLONEDDS_URI names (files or inline XML), holds a <Security> element. Not real-time safe.
bool dds_security_configured(const std::string& config_file);

}  // namespace rpsd::operator_commands
