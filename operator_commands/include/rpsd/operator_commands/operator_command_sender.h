// The sending side of operator commands (`rpsd stop`, the monitor's page): one DDS participant
// on the test's operator partition with a command writer and a reply reader. With DDS Security
// on, only an identity whose permissions grant the operator role may write the command topic;
// with it off, only a run whose scenario enables operator commands acts on them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "rpsd/operator_commands/operator_command.h"

namespace rpsd::operator_commands {

struct OperatorLinkConfig {
  std::uint32_t domain_id = 0;
  std::string dds_config;  // Cyclone XML (with the operator's identity when security is on); empty: CYCLONEDDS_URI
  std::uint32_t test_id = 1;
};

class OperatorCommandSender {
 public:
  // Joins the domain and the test's operator partition. Not real-time safe; throws
  // std::runtime_error (transport::DdsError) naming the failing call or an unreadable file.
  // sender_name (at most 63 bytes are sent) is who the coordinator logs: "alice@rig-pc".
  OperatorCommandSender(const OperatorLinkConfig& config, std::string sender_name);
  ~OperatorCommandSender();
  OperatorCommandSender(const OperatorCommandSender&) = delete;
  OperatorCommandSender& operator=(const OperatorCommandSender&) = delete;

  // Sends the command and waits up to timeout_s for the coordinator's reply (the command is
  // repeated under the same sequence number until answered, so one lost while discovery
  // finishes still arrives; the coordinator acts once per sequence). nullopt when no reply
  // came: no run of the test, or the DDS security of the domain let neither through.
  // Thread-safe: several callers (browsers) may send at once. Not real-time safe.
  std::optional<OperatorReply> send(OperatorAction action, double timeout_s);

  // The name sent with every command (as truncated on the wire).
  const std::string& sender_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "stop", "abort", "hold", "resume".
const char* operator_action_name(OperatorAction action);

}  // namespace rpsd::operator_commands
