// An operator's commands acted on by a whole in-process lock-step test (operator_commands/):
// the stop ends it after the step under way with every step recorded, its return to the
// start positions ramps at the stated velocity through the exchange, the abort ends it at once,
// a hold leaves the history unchanged, and a run that does not accept them refuses them.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "../servo/paper_rig.h"
#include "claimed_dds_domain.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/hybrid_test/operator_listener.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::hybrid_test {
namespace {

using coordinator::StepOutcome;
using operator_commands::OperatorControl;

TestConfig elcentro(const std::vector<std::string>& overrides = {}) {
  std::vector<scenarios::Override> o{scenarios::parse_override("ground_motion.trim={end_s: 6}")};
  for (const auto& text : overrides) o.push_back(scenarios::parse_override(text));
  const auto file = scenarios::load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml", o);
  return std::get<TestConfig>(file.study);
}

// Runs the test as fast as possible in this process, with `act` called after each step.
TestRun run_with(const TestConfig& s, OperatorControl& control, const std::function<void(std::int64_t)>& act,
                 const std::filesystem::path& csv = {}) {
  AssemblyOptions options;
  options.csv = csv;
  options.keep_records = true;
  options.operator_control = &control;
  TestAssembly test(s, options);
  const StepOutcome outcome = test.run([&](const coordinator::StepRecord& r) { act(r.step); }, {});
  return test.finish(outcome);
}

// Waits until the loop holds (a hang guard of 20 s, not a timing): true when it does.
bool wait_until_holding(const OperatorControl& control) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!control.holding()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(OperatorCommands, AStopEndsALockStepRunAfterTheStepUnderWayWithEveryStepRecorded) {
  const TestConfig s = elcentro();
  OperatorControl control;
  const TestRun run = run_with(s, control, [&](std::int64_t step) {
    if (step == 1500) control.request_stop("alice@rig");
  });
  EXPECT_EQ(run.outcome, StepOutcome::kOperatorStop);
  EXPECT_STREQ(coordinator::step_outcome_name(run.outcome), "operator_stop");
  EXPECT_EQ(run.steps, 1500);
  ASSERT_EQ(run.records.size(), 1500u);
  for (std::size_t i = 0; i < run.records.size(); ++i) ASSERT_EQ(run.records[i].step, static_cast<std::int64_t>(i + 1));
  EXPECT_EQ(run.operator_sender, "alice@rig");
  EXPECT_FALSE(run.return_to_start.asked);
  EXPECT_LT(run.steps, run.steps_planned);
}

TEST(OperatorCommands, ReturnToStartRampsEachTargetAtTheStatedVelocityThroughTheExchangeAndEndsAtTheStart) {
  constexpr double kVelocity = 0.02;
  const TestConfig s = elcentro({"operator_commands={return_to_start: true, return_velocity_m_per_s: 0.02}"});
  OperatorControl control;
  // Stopped at 2.9 s, near the record's strong motion: the target is far from the start (0).
  const TestRun run = run_with(s, control, [&](std::int64_t step) {
    if (step == 2970) control.request_stop("alice");
  });
  ASSERT_EQ(run.outcome, StepOutcome::kOperatorStop);
  const ReturnToStart& r = run.return_to_start;
  ASSERT_TRUE(r.asked);
  ASSERT_EQ(r.outcome, StepOutcome::kOk);
  ASSERT_EQ(r.channels, 1);
  // The ramp starts where the last command was, uncompensated: no jump on its first exchange.
  const double from = run.records.back().command_m[0];
  ASSERT_GT(std::abs(from), 2e-3) << "the stop must leave the command away from the start";
  const double dt = 1.0 / s.control_rate_hz;
  const auto ramp = static_cast<std::int64_t>(std::ceil(std::abs(from) / (kVelocity * dt)));
  ASSERT_GT(r.exchanges, ramp);  // the ramp, then the settling at the start
  const double t0 = run.records.back().time_s;
  for (std::int64_t k = 1; k <= r.exchanges; ++k) {
    const double* row = r.rows.data() + (k - 1) * 5;
    const double analytic =
        from - std::copysign(std::min(std::abs(from), kVelocity * dt * static_cast<double>(k)), from);
    ASSERT_NEAR(row[0], t0 + dt * static_cast<double>(k), 1e-9) << "exchange " << k;
    ASSERT_NEAR(row[1], analytic, 1e-12) << "exchange " << k;
    ASSERT_EQ(row[2], row[1]) << "exchange " << k << ": the return's command is its target";
  }
  const double* last = r.rows.data() + (r.exchanges - 1) * 5;
  EXPECT_EQ(last[1], 0.0);
  // The simulated actuator has settled on the start: within 1 % of the way it came back.
  EXPECT_NEAR(last[3], 0.0, 0.01 * std::abs(from));
}

TEST(OperatorCommands, AnAbortEndsTheRunAtOnceAndNeverReturnsToStart) {
  const TestConfig s = elcentro({"operator_commands={return_to_start: true, return_velocity_m_per_s: 0.02}"});
  OperatorControl control;
  const TestRun run = run_with(s, control, [&](std::int64_t step) {
    if (step == 800) control.request_abort("bob");
  });
  EXPECT_EQ(run.outcome, StepOutcome::kOperatorAbort);
  EXPECT_EQ(run.steps, 800);
  EXPECT_EQ(run.operator_sender, "bob");
  EXPECT_FALSE(run.return_to_start.asked);
}

TEST(OperatorCommands, AHeldAndResumedRunWritesTheSameHistoryAsAnUnheldOneByteForByte) {
  const TestConfig s = elcentro();
  const auto dir = std::filesystem::temp_directory_path() / ("rpsd-held-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  OperatorControl unheld_control, control;
  const TestRun unheld = run_with(
      s, unheld_control, [](std::int64_t) {}, dir / "unheld.csv");
  std::thread resumer;
  const TestRun held = run_with(
      s, control,
      [&](std::int64_t step) {
        if (step != 2000) return;
        control.request_hold("alice");
        resumer = std::thread([&] {
          if (wait_until_holding(control)) std::this_thread::sleep_for(std::chrono::milliseconds(30));
          control.request_resume("bob");
        });
      },
      dir / "held.csv");
  resumer.join();
  EXPECT_EQ(held.outcome, StepOutcome::kOk);
  EXPECT_EQ(held.steps, unheld.steps);
  ASSERT_EQ(held.held.size(), 1u);
  EXPECT_EQ(held.held[0].after_step, 2000);
  EXPECT_EQ(held.held[0].held_by, "alice");
  EXPECT_EQ(held.held[0].resumed_by, "bob");
  EXPECT_GT(held.held[0].end_unix_ns, held.held[0].start_unix_ns);
  const std::string a = file_text(dir / "unheld.csv"), b = file_text(dir / "held.csv");
  EXPECT_GT(a.size(), 100000u);
  EXPECT_TRUE(a == b) << "the held run's time history differs from the unheld run's";
  std::filesystem::remove_all(dir);
}

TEST(OperatorCommands, AStopWhileHeldEndsTheRunAndRecordsTheOpenInterval) {
  const TestConfig s = elcentro();
  OperatorControl control;
  std::thread stopper;
  const TestRun run = run_with(s, control, [&](std::int64_t step) {
    if (step != 100) return;
    control.request_hold("alice");
    stopper = std::thread([&] {
      (void)wait_until_holding(control);
      control.request_stop("carol");
    });
  });
  stopper.join();
  EXPECT_EQ(run.outcome, StepOutcome::kOperatorStop);
  EXPECT_EQ(run.steps, 100);
  ASSERT_EQ(run.held.size(), 1u);
  EXPECT_EQ(run.held[0].end_unix_ns, 0);
  EXPECT_EQ(run.operator_sender, "carol");
}

// Over the loopback DDS configuration, in a domain of this test binary's own.
TestConfig over_loopback(TestConfig s, std::uint32_t test_id) {
  s.transport.domain_id = ::rpsd::testing::claimed_dds_domain();
  s.transport.dds_config = testing::source_dir() / "transport/config/loopback.xml";
  s.transport.test_id = test_id;
  return s;
}

TEST(OperatorCommands, ARunInProcessThatDoesNotEnableThemHearsNoneAndMakesNoParticipant) {
  OperatorControl control;
  EXPECT_EQ(listen_for_operators(over_loopback(elcentro(), 31), 1, false, control), nullptr);
}

TEST(OperatorCommands, ARunOverDdsThatDoesNotEnableThemRefusesThemAndLogsThem) {
  TestConfig s = over_loopback(elcentro(), 32);
  s.transport.kind = TransportConfig::Kind::kDds;
  OperatorControl control;
  const auto listener = listen_for_operators(s, 5, false, control);
  ASSERT_NE(listener, nullptr);
  operator_commands::OperatorCommandSender sender({s.transport.domain_id, s.transport.dds_config.string(), 32},
                                                  "stranger");
  const auto reply = sender.send(operator_commands::OperatorAction::kStop, 20.0);  // a hang guard
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->status, operator_commands::ReplyStatus::kRefused);
  EXPECT_NE(std::string(reply->text.data()).find("operator_commands.enabled"), std::string::npos) << reply->text.data();
  EXPECT_EQ(control.request(), operator_commands::OperatorRequest::kNone);
  ASSERT_EQ(listener->log().size(), 1u);
  EXPECT_EQ(listener->log()[0].sender, "stranger");
}

TEST(OperatorCommands, AHoldIsRefusedInRealTimeAndAStopTaken) {
  TestConfig s = over_loopback(elcentro({"operator_commands={enabled: true}"}), 33);
  OperatorControl control;
  const auto listener = listen_for_operators(s, 5, true, control);
  ASSERT_NE(listener, nullptr);
  operator_commands::OperatorCommandSender sender({s.transport.domain_id, s.transport.dds_config.string(), 33}, "op");
  const auto hold = sender.send(operator_commands::OperatorAction::kHold, 20.0);
  ASSERT_TRUE(hold.has_value());
  EXPECT_EQ(hold->status, operator_commands::ReplyStatus::kRefused);
  EXPECT_NE(std::string(hold->text.data()).find("real-time test cannot hold"), std::string::npos);
  EXPECT_FALSE(control.hold_requested());
  EXPECT_EQ(sender.send(operator_commands::OperatorAction::kStop, 20.0)->status, operator_commands::ReplyStatus::kDone);
  EXPECT_EQ(control.request(), operator_commands::OperatorRequest::kStop);
}

}  // namespace
}  // namespace rpsd::hybrid_test
