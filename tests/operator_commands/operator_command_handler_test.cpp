// The coordinator's decision on each operator command, apart from DDS: which flag of the loop
// it sets, what it answers and what it logs.
#include "rpsd/operator_commands/operator_command_handler.h"

#include <gtest/gtest.h>

#include <string>

namespace rpsd::operator_commands {
namespace {

constexpr std::uint64_t kRun = 0x1234;

OperatorHandlerOptions accepting(bool real_time = false) {
  OperatorHandlerOptions o;
  o.test_id = 7;
  o.run_id = kRun;
  o.accepting = true;
  o.real_time = real_time;
  o.print_to_stderr = false;
  return o;
}

OperatorCommand command(OperatorAction action, std::uint64_t sequence, const std::string& who = "alice@rig") {
  OperatorCommand c;
  c.test_id = 7;
  c.action = action;
  c.sequence = sequence;
  c.sent_unix_ns = 1000;
  copy_text(who, c.sender);
  return c;
}

std::string text(const OperatorReply& r) { return r.text.data(); }

TEST(OperatorCommandHandler, StopSetsTheLoopsStopFlagAnswersDoneAndLogsWhoAndWhen) {
  OperatorControl control;
  OperatorCommandHandler handler(accepting(), control);
  const auto reply = handler.handle(command(OperatorAction::kStop, 1), 5000);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->status, ReplyStatus::kDone);
  EXPECT_EQ(reply->sequence, 1u);
  EXPECT_EQ(reply->run_id, kRun);
  EXPECT_EQ(control.request(), OperatorRequest::kStop);
  EXPECT_EQ(control.requested_by(), "alice@rig");
  const auto log = handler.log();
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].sender, "alice@rig");
  EXPECT_EQ(log[0].received_unix_ns, 5000);
  EXPECT_EQ(log[0].sent_unix_ns, 1000);
  EXPECT_EQ(log[0].status, ReplyStatus::kDone);
}

TEST(OperatorCommandHandler, AnAbortReplacesAStopAndAStopNeverReplacesAnAbort) {
  OperatorControl control;
  OperatorCommandHandler handler(accepting(), control);
  (void)handler.handle(command(OperatorAction::kStop, 1), 1);
  EXPECT_EQ(handler.handle(command(OperatorAction::kAbort, 2, "bob"), 2)->status, ReplyStatus::kDone);
  EXPECT_EQ(control.request(), OperatorRequest::kAbort);
  EXPECT_EQ(control.requested_by(), "bob");
  const auto stop = handler.handle(command(OperatorAction::kStop, 3), 3);
  EXPECT_EQ(stop->status, ReplyStatus::kRefused);
  EXPECT_EQ(control.request(), OperatorRequest::kAbort);
}

TEST(OperatorCommandHandler, HoldAndResumeToggleTheHoldFlagOnceEach) {
  OperatorControl control;
  OperatorCommandHandler handler(accepting(), control);
  EXPECT_EQ(handler.handle(command(OperatorAction::kResume, 1), 1)->status, ReplyStatus::kRefused);
  EXPECT_EQ(handler.handle(command(OperatorAction::kHold, 2), 2)->status, ReplyStatus::kDone);
  EXPECT_TRUE(control.hold_requested());
  EXPECT_EQ(control.held_by(), "alice@rig");
  const auto again = handler.handle(command(OperatorAction::kHold, 3), 3);
  EXPECT_EQ(again->status, ReplyStatus::kRefused);
  EXPECT_NE(text(*again).find("already held"), std::string::npos) << text(*again);
  EXPECT_EQ(handler.handle(command(OperatorAction::kResume, 4, "bob"), 4)->status, ReplyStatus::kDone);
  EXPECT_FALSE(control.hold_requested());
  EXPECT_EQ(control.resumed_by(), "bob");
  EXPECT_EQ(handler.log().size(), 4u);  // refused ones too
}

TEST(OperatorCommandHandler, HoldAndResumeAreRefusedInRealTimeWithAReplySayingWhy) {
  OperatorControl control;
  OperatorCommandHandler handler(accepting(true), control);
  const auto hold = handler.handle(command(OperatorAction::kHold, 1), 1);
  ASSERT_TRUE(hold.has_value());
  EXPECT_EQ(hold->status, ReplyStatus::kRefused);
  EXPECT_NE(text(*hold).find("real-time"), std::string::npos) << text(*hold);
  EXPECT_FALSE(control.hold_requested());
  EXPECT_EQ(handler.handle(command(OperatorAction::kResume, 2), 2)->status, ReplyStatus::kRefused);
  // A stop is still taken in real time.
  EXPECT_EQ(handler.handle(command(OperatorAction::kStop, 3), 3)->status, ReplyStatus::kDone);
}

TEST(OperatorCommandHandler, ARunThatDoesNotAcceptCommandsRefusesEveryOneChangesNothingAndLogsIt) {
  OperatorControl control;
  OperatorHandlerOptions o = accepting();
  o.accepting = false;
  o.not_accepting_reason = "not enabled";
  OperatorCommandHandler handler(o, control);
  for (auto [action, seq] :
       {std::pair{OperatorAction::kStop, 1}, {OperatorAction::kAbort, 2}, {OperatorAction::kHold, 3}}) {
    const auto reply = handler.handle(command(action, static_cast<std::uint64_t>(seq)), seq);
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(reply->status, ReplyStatus::kRefused);
    EXPECT_NE(text(*reply).find("not enabled"), std::string::npos);
  }
  EXPECT_EQ(control.request(), OperatorRequest::kNone);
  EXPECT_FALSE(control.hold_requested());
  EXPECT_EQ(handler.log().size(), 3u);
}

TEST(OperatorCommandHandler, ACommandRepeatedUnderItsSequenceIsAnsweredAgainButActedOnOnce) {
  OperatorControl control;
  OperatorCommandHandler handler(accepting(), control);
  const auto first = handler.handle(command(OperatorAction::kHold, 10), 1);
  (void)handler.handle(command(OperatorAction::kResume, 11), 2);
  // The hold's late repeat (the sender repeats until answered) must not hold the test again.
  EXPECT_FALSE(handler.handle(command(OperatorAction::kHold, 10), 3).has_value());
  EXPECT_FALSE(control.hold_requested());
  const auto repeat = handler.handle(command(OperatorAction::kResume, 11), 4);
  ASSERT_TRUE(repeat.has_value());
  EXPECT_EQ(repeat->status, ReplyStatus::kDone);  // the same answer, not "not held"
  EXPECT_EQ(handler.log().size(), 2u);
  EXPECT_EQ(first->status, ReplyStatus::kDone);
}

TEST(OperatorCommandHandler, ACommandForAnotherRunIsLoggedButNeitherActedOnNorAnswered) {
  OperatorControl control;
  OperatorCommandHandler handler(accepting(), control);
  OperatorCommand c = command(OperatorAction::kStop, 1);
  c.run_id = kRun + 1;
  EXPECT_FALSE(handler.handle(c, 1).has_value());
  c.run_id = 0;
  c.test_id = 8;
  EXPECT_FALSE(handler.handle(c, 2).has_value());
  EXPECT_EQ(control.request(), OperatorRequest::kNone);
  EXPECT_EQ(handler.log().size(), 2u);
}

TEST(OperatorCommandHandler, TheHookSeesEveryCommandLogged) {
  OperatorControl control;
  OperatorHandlerOptions o = accepting();
  std::vector<OperatorCommandEvent> seen;
  o.on_command = [&](const OperatorCommandEvent& e) { seen.push_back(e); };
  OperatorCommandHandler handler(o, control);
  (void)handler.handle(command(OperatorAction::kHold, 1), 1);
  (void)handler.handle(command(OperatorAction::kHold, 2), 2);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].status, ReplyStatus::kDone);
  EXPECT_EQ(seen[1].status, ReplyStatus::kRefused);
}

}  // namespace
}  // namespace rpsd::operator_commands
