// The listener→flag path over DDS: a sender and the coordinator's listener in one process on
// the loopback configuration; the command reaches the loop's flag and its reply the sender.
#include "rpsd/operator_commands/operator_command_listener.h"
#include "claimed_dds_domain.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

namespace rpsd::operator_commands {
namespace {

OperatorLinkConfig loopback(std::uint32_t test_id) {
  // A domain no other live test holds (claimed_dds_domain.h) keeps parallel ctest processes apart.
  return {::rpsd::testing::claimed_dds_domain(), std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/loopback.xml",
          test_id};
}

OperatorHandlerOptions options(std::uint32_t test_id, bool accepting) {
  OperatorHandlerOptions o;
  o.test_id = test_id;
  o.run_id = 99;
  o.accepting = accepting;
  o.not_accepting_reason = "not enabled here";
  o.print_to_stderr = false;
  return o;
}

TEST(OperatorCommandListener, AStopSentOverDdsSetsTheLoopsFlagAndIsAnsweredDone) {
  OperatorControl control;
  OperatorCommandListener listener(loopback(21), options(21, true), control);
  OperatorCommandSender sender(loopback(21), "alice@rig (test)");
  const auto reply = sender.send(OperatorAction::kStop, 20.0);  // a hang guard, not a timing
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->status, ReplyStatus::kDone);
  EXPECT_EQ(reply->run_id, 99u);
  EXPECT_EQ(control.request(), OperatorRequest::kStop);
  const auto log = listener.log();
  ASSERT_EQ(log.size(), 1u);  // repeats while discovery finished are acted on once
  EXPECT_EQ(log[0].sender, "alice@rig (test)");
  EXPECT_EQ(log[0].action, OperatorAction::kStop);
}

TEST(OperatorCommandListener, HoldThenResumeOverDdsToggleTheHoldFlag) {
  OperatorControl control;
  OperatorCommandListener listener(loopback(22), options(22, true), control);
  OperatorCommandSender sender(loopback(22), "bob");
  ASSERT_EQ(sender.send(OperatorAction::kHold, 20.0)->status, ReplyStatus::kDone);
  EXPECT_TRUE(control.hold_requested());
  ASSERT_EQ(sender.send(OperatorAction::kResume, 20.0)->status, ReplyStatus::kDone);
  EXPECT_FALSE(control.hold_requested());
  EXPECT_EQ(control.request(), OperatorRequest::kNone);
}

TEST(OperatorCommandListener, ARunNotAcceptingCommandsAnswersRefusedAndSetsNothing) {
  OperatorControl control;
  OperatorCommandListener listener(loopback(23), options(23, false), control);
  OperatorCommandSender sender(loopback(23), "stranger");
  const auto reply = sender.send(OperatorAction::kAbort, 20.0);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->status, ReplyStatus::kRefused);
  EXPECT_NE(std::string(reply->text.data()).find("not enabled here"), std::string::npos);
  EXPECT_EQ(control.request(), OperatorRequest::kNone);
  EXPECT_EQ(listener.log().size(), 1u);
}

TEST(OperatorCommandListener, NoRunOfTheTestMeansNoAnswer) {
  OperatorControl control;
  OperatorCommandListener other_test(loopback(24), options(24, true), control);
  OperatorCommandSender sender(loopback(25), "alice");
  EXPECT_FALSE(sender.send(OperatorAction::kStop, 0.5).has_value());
  EXPECT_EQ(control.request(), OperatorRequest::kNone);  // another test's partition
}

TEST(DdsSecurityConfigured, ReadsTheSecuritySectionOfTheNamedConfiguration) {
  const std::string dir = std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/";
  EXPECT_FALSE(dds_security_configured(dir + "loopback.xml"));
  EXPECT_TRUE(dds_security_configured(dir + "security/loopback-secure.xml"));
}

}  // namespace
}  // namespace rpsd::operator_commands
