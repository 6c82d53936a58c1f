// `rpsd stop --test-id N [--abort | --hold | --resume]`: an operator's command to a running test
// over DDS (operator_commands/), its reply printed. Exit 0 done, 7 refused, 8 no answer.
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <memory>

#include "rpsd/commands.h"
#include "rpsd/operator_commands/operator_command_sender.h"

namespace rpsd::cli {
namespace {

struct StopOptions {
  std::uint32_t test_id = 1;
  std::uint32_t domain = 0;
  std::string dds_config;
  double timeout_s = 5.0;
  bool abort = false, hold = false, resume = false;
  std::string sender;
};

// "user@host (rpsd stop)": who the coordinator logs when --sender names no one.
std::string default_sender() {
  const char* user = std::getenv("USER");
  char host[64] = "";
  gethostname(host, sizeof host - 1);
  return std::string(user && *user ? user : "unknown") + "@" + host + " (rpsd stop)";
}

}  // namespace

void add_stop(CLI::App& app) {
  auto o = std::make_shared<StopOptions>();
  auto* stop = app.add_subcommand(
      "stop",
      "Send an operator command to a running test over DDS and print its reply: stop (default: ends in order; "
      "returns to the start positions when the scenario asks), --abort (every node holds at once), --hold or "
      "--resume (lock-step only). Exit 0 done, 7 refused by the test, 8 no answer. The rig's hardware emergency "
      "stop stays the primary stop.");
  stop->add_option("--test-id", o->test_id, "The test's id (its scenario's transport.test_id)")->required();
  auto* abort =
      stop->add_flag("--abort", o->abort, "Abort: the coordinator stops commanding, every node holds at once");
  auto* hold = stop->add_flag("--hold", o->hold, "Hold a lock-step test between two steps (refused in real time)");
  auto* resume = stop->add_flag("--resume", o->resume, "Resume a held lock-step test from the step where it held");
  abort->excludes(hold)->excludes(resume);
  hold->excludes(resume);
  stop->add_option("--domain", o->domain, "DDS domain (default 0)")->check(CLI::Range(0, 232));
  stop->add_option("--dds-config", o->dds_config,
                   "Cyclone DDS XML; with DDS Security on it names the operator's identity")
      ->check(CLI::ExistingFile);
  stop->add_option("--timeout", o->timeout_s, "Seconds to wait for the test's reply (default 5)")
      ->check(CLI::Range(0.0, 3600.0));
  stop->add_option("--sender", o->sender, "Who the test logs as the sender (default: user@host (rpsd stop))");
  stop->callback([o] {
    using operator_commands::OperatorAction;
    const OperatorAction action = o->abort    ? OperatorAction::kAbort
                                  : o->hold   ? OperatorAction::kHold
                                  : o->resume ? OperatorAction::kResume
                                              : OperatorAction::kStop;
    std::unique_ptr<operator_commands::OperatorCommandSender> made;
    try {
      made = std::make_unique<operator_commands::OperatorCommandSender>(
          operator_commands::OperatorLinkConfig{o->domain, o->dds_config, o->test_id},
          o->sender.empty() ? default_sender() : o->sender);
    } catch (const operator_commands::OperatorNotPermitted& e) {
      throw OperatorCommandRefused(o->test_id, e.what());
    }
    operator_commands::OperatorCommandSender& sender = *made;
    const auto reply = sender.send(action, o->timeout_s);
    if (!reply) throw NoOperatorReply(o->test_id, operator_commands::operator_action_name(action), o->timeout_s);
    const std::string text(reply->text.data());
    if (reply->status != operator_commands::ReplyStatus::kDone) throw OperatorCommandRefused(o->test_id, text);
    std::cout << "rpsd stop: test " << o->test_id << ": done: " << text << "\n";
  });
}

}  // namespace rpsd::cli
