// The servo node's logic with an ideal actuator (measured displacement = command, load cell
// = k x): each limit with each action, the watchdog (hold, ramp to safe), and every kind of
// bad command dropped, counted and never applied. Limits and rates are powers of two where
// a test asserts exact increments, so that the expected values are exact in binary.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nees_plugin_test_site.h"
#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/servo_node_controller.h"
#include "rpsd/node/udp_controller_actuator.h"
#include "rpsd/servo/transfer_function_plant.h"
#include "udp_test_link.h"

namespace rpsd::node {
namespace {

using transport::CommandSample;
using transport::FeedbackSample;

class IdealActuator final : public servo::Actuator {
 public:
  explicit IdealActuator(int channels, double stiffness_n_per_m = 0.0)
      : channels_(channels), stiffness_(stiffness_n_per_m) {}
  int channels() const override { return channels_; }
  void start(std::span<const double> x0) override {
    started_at.assign(x0.begin(), x0.end());
    commands.clear();
  }
  servo::ActuatorStatus exchange(std::span<const double> command_m, double period_s,
                                 servo::ActuatorReading& reading) override {
    commands.emplace_back(command_m.begin(), command_m.end());
    periods.push_back(period_s);
    const servo::ActuatorStatus status = script.empty() ? servo::ActuatorStatus::kOk : script.front();
    if (!script.empty()) script.pop_front();
    if (status == servo::ActuatorStatus::kNoReply) {
      reading.fresh = false;
      return status;
    }
    for (int c = 0; c < channels_; ++c) {
      reading.displacement_m[c] = command_m[c] + measured_offset_m;
      reading.force_n[c] = stiffness_ * reading.displacement_m[c];
    }
    reading.fresh = true;
    return status;
  }
  std::string_view fault_text() const noexcept override { return fault_words; }
  double last(int channel = 0) const { return commands.back()[channel]; }

  std::vector<double> started_at;
  std::vector<std::vector<double>> commands;
  std::vector<double> periods;
  std::deque<servo::ActuatorStatus> script;  // statuses to return, then kOk
  double measured_offset_m = 0.0;            // a piston that drifts from its command (a fault)
  std::string fault_words;                   // what it says when it faults

 private:
  int channels_;
  double stiffness_;
};

constexpr std::uint32_t kTest = 7, kSite = 3;
constexpr std::uint64_t kRun = 0x7e57;
constexpr double kPeriod = 1.0 / 1024.0;

ServoNodeConfig config(int channels = 1) {
  ServoNodeConfig c;
  c.test_id = kTest;
  c.site_id = kSite;
  c.channels = channels;
  c.control_period_s = kPeriod;
  c.command_timeout_periods = 1000;
  return c;
}

CommandSample command(std::int64_t step, std::initializer_list<double> x) {
  CommandSample c;
  c.test_id = kTest;
  c.site_id = kSite;
  c.run_id = kRun;
  c.step = step;
  c.time_s = static_cast<double>(step) * kPeriod;
  c.channels = static_cast<std::uint8_t>(x.size());
  int i = 0;
  for (double v : x) c.displacement_m[i++] = v;
  return c;
}

// Accepts the command and runs one tick; returns the feedback.
FeedbackSample send(ServoNodeController& node, const CommandSample& c) {
  EXPECT_EQ(node.accept(c), CommandVerdict::kAccepted) << c.step;
  FeedbackSample out;
  node.tick(out);
  return out;
}

// An ideal actuator and a node started at zero.
struct NodeRig {
  explicit NodeRig(const ServoNodeConfig& c, double stiffness_n_per_m = 0.0)
      : actuator(c.channels, stiffness_n_per_m), node(c, actuator) {
    const std::vector<double> x0(static_cast<std::size_t>(c.channels), 0.0);
    node.start(x0);
  }
  IdealActuator actuator;
  ServoNodeController node;
};

FeedbackSample idle(ServoNodeController& node) {
  FeedbackSample out;
  node.tick(out);
  return out;
}

std::string config_error(const ServoNodeConfig& c) {
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// The force guard predicts the force a command would bring (measured force plus the guard's
// stiffness times the move): a command beyond where it reaches max_force_n stops there, and the
// guard says so on that tick, in the flags and once in the log, with the force it predicted.
TEST(ServoNodeController, TheForceGuardFlagsAndLogsTheForceItPredicts) {
  auto c = config();
  c.limits[0].max_force_n = 1000.0;
  c.limits[0].force_guard_stiffness_n_per_m = 1e5;
  c.actions.force = LimitAction::kClamp;
  NodeRig rig(c, 1e5);                     // the specimen as stiff as the guard thinks
  rig.actuator.measured_offset_m = 0.001;  // the piston 1 mm beyond its command: the guard uses where it is
  FeedbackSample out = send(rig.node, command(0, {0.005}));  // at 6 mm, 600 N: within
  EXPECT_EQ(out.limit_flags, transport::kLimitNone);
  out = send(rig.node, command(1, {0.02}));  // 600 N + 1e5 N/m x (20 - 6) mm = 2000 N predicted
  EXPECT_NE(out.limit_flags & transport::kLimitForce, 0u);
  EXPECT_NE(out.status & transport::kNodeLimitActive, 0u);
  EXPECT_NEAR(out.displacement_m[0], 0.011, 1e-12);  // sent 10 mm, where the guard reaches 1000 N
  ASSERT_EQ(rig.node.events().size(), 1u);
  const LimitEvent& e = rig.node.events().front();
  EXPECT_EQ(e.kind, LimitKind::kForce);
  EXPECT_EQ(e.cause, LimitCause::kLimit);
  EXPECT_NEAR(e.observed, 2000.0, 1e-6);
  EXPECT_EQ(e.bound, 1000.0);
  EXPECT_EQ(e.commanded_m, 0.02);
  EXPECT_NEAR(e.applied_m, 0.01, 1e-12);
  out = send(rig.node, command(2, {0.02}));  // still asked for: acting, not logged again
  EXPECT_NE(out.limit_flags & transport::kLimitForce, 0u);
  EXPECT_EQ(rig.node.events().size(), 1u);
  EXPECT_EQ(rig.node.counters().activations(LimitKind::kForce), 1u);
  EXPECT_FALSE(rig.node.faulted());
}

TEST(ServoNodeController, ConfigErrorsNameTheField) {
  EXPECT_EQ(config_error(config()), "");
  auto c = config();
  c.channels = 0;
  EXPECT_EQ(config_error(c).rfind("channels:", 0), 0u);
  c = config();
  c.control_period_s = -1e-3;
  EXPECT_EQ(config_error(c).rfind("control_period_s:", 0), 0u);
  c = config(2);
  c.limits[1].max_stroke_m = 0.0;
  EXPECT_EQ(config_error(c).rfind("limits[1].max_stroke_m:", 0), 0u) << config_error(c);
  c = config(2);
  c.limits[0].max_force_n = std::nan("");
  EXPECT_EQ(config_error(c).rfind("limits[0].max_force_n:", 0), 0u);
  c = config();
  c.limits[0].max_velocity_m_per_s = -1.0;
  EXPECT_EQ(config_error(c).rfind("limits[0].max_velocity_m_per_s:", 0), 0u);
  c = config();
  c.limits[0].max_increment_m = 0.0;
  EXPECT_EQ(config_error(c).rfind("limits[0].max_increment_m:", 0), 0u);
  c = config();
  c.limits[0].max_increment_m_per_s = -0.1;
  EXPECT_EQ(config_error(c).rfind("limits[0].max_increment_m_per_s:", 0), 0u);
  c = config();
  c.command_timeout_periods = 0;
  EXPECT_EQ(config_error(c).rfind("command_timeout_periods:", 0), 0u);
  // The watchdog's timeout is bounded: a rate of 1e-300 Hz would stretch it to never.
  c = config();
  c.command_timeout_periods = 10;
  c.control_period_s = 1.0;
  EXPECT_EQ(config_error(c), "");
  c.control_period_s = 1e300;
  EXPECT_EQ(config_error(c).rfind("command_timeout_periods: times the control period (1/control_rate_hz) is the "
                                  "watchdog's timeout, at most 10 s, here 1e+301 s",
                                  0),
            0u)
      << config_error(c);
  c.control_period_s = 1.0;
  c.command_timeout_periods = 11;
  EXPECT_EQ(config_error(c).rfind("command_timeout_periods:", 0), 0u);
  c = config(2);
  c.on_command_loss = LossAction::kRampToSafe;
  c.limits[1].max_stroke_m = 0.05;
  c.safe_position_m[1] = 0.06;
  EXPECT_EQ(config_error(c).rfind("safe_position_m[1]: must lie within limits[1].max_stroke_m", 0), 0u)
      << config_error(c);
  c.safe_position_m[1] = 0.0;
  c.limits[0].max_velocity_m_per_s = 0.001;
  EXPECT_EQ(config_error(c).rfind("safe_ramp_velocity_m_per_s: must not exceed limits[0].max_velocity_m_per_s", 0), 0u);
  c.limits[0].max_velocity_m_per_s = 1.0;
  c.safe_ramp_velocity_m_per_s = 0.0;
  EXPECT_EQ(config_error(c).rfind("safe_ramp_velocity_m_per_s:", 0), 0u);

  IdealActuator two(2);
  EXPECT_THROW(ServoNodeController(config(1), two), std::invalid_argument);
  auto bad = config();
  bad.channels = 9;
  IdealActuator one(1);
  EXPECT_THROW(ServoNodeController(bad, one), std::invalid_argument);
}

TEST(ServoNodeController, AppliesEachCommandOnTheNextTickAndReportsIt) {
  IdealActuator actuator(2, 1e5);
  ServoNodeController node(config(2), actuator);
  FeedbackSample out;
  node.tick(out);  // before start(): a fault, nothing sent
  EXPECT_EQ(out.status, transport::kNodeFault);
  EXPECT_TRUE(actuator.commands.empty());

  const double x0[] = {0.001, -0.002};
  node.start(x0);
  EXPECT_EQ(actuator.started_at, std::vector<double>({0.001, -0.002}));
  // Before the first command the node holds its start position without calling it a loss.
  for (int i = 0; i < 50; ++i) out = idle(node);
  EXPECT_EQ(out.status, transport::kNodeOk);
  EXPECT_EQ(out.step, -1);
  EXPECT_EQ(actuator.last(1), -0.002);
  EXPECT_EQ(node.counters().missed_periods, 0u);

  ASSERT_EQ(node.accept(command(0, {0.003, 0.004})), CommandVerdict::kAccepted);
  EXPECT_EQ(actuator.last(0), 0.001);  // accept() alone moves nothing
  node.tick(out);
  EXPECT_EQ(actuator.last(0), 0.003);
  EXPECT_EQ(actuator.last(1), 0.004);
  EXPECT_EQ(actuator.periods.back(), kPeriod);
  EXPECT_EQ(out.test_id, kTest);
  EXPECT_EQ(out.site_id, kSite);
  EXPECT_EQ(out.step, 0);
  EXPECT_EQ(out.time_s, 0.0);
  EXPECT_EQ(out.channels, 2);
  EXPECT_EQ(out.displacement_m[1], 0.004);
  EXPECT_EQ(out.force_n[0], 1e5 * 0.003);
  EXPECT_EQ(out.status, transport::kNodeOk);
  EXPECT_EQ(out.limit_flags, transport::kLimitNone);
  out = send(node, command(1, {0.0031, 0.0041}));
  EXPECT_EQ(out.step, 1);
  EXPECT_EQ(out.time_s, kPeriod);
  EXPECT_EQ(node.counters().applied, 2u);
  EXPECT_EQ(node.counters().ticks, 52u);
}

// Issue 30: what the node's heartbeat carries. Nothing is measured after start() until the
// actuator answers an exchange (or the reading at rest is noted); then each answered tick's
// reading, holding too, and an exchange without a reply keeps the newest one.
TEST(ServoNodeController, TheLatestMeasurementIsTheNewestAnsweredExchange) {
  NodeRig rig(config(2), 1e5);
  EXPECT_FALSE(rig.node.has_measurement());
  servo::ActuatorReading at_rest;
  at_rest.displacement_m[0] = 0.0025;
  at_rest.force_n[1] = -40.0;
  rig.node.note_reading_at_rest(at_rest);
  EXPECT_TRUE(rig.node.has_measurement());
  EXPECT_EQ(rig.node.latest_measurement().displacement_m[0], 0.0025);
  EXPECT_EQ(rig.node.latest_measurement().force_n[1], -40.0);
  EXPECT_TRUE(rig.actuator.commands.empty());  // noted, not exchanged

  rig.actuator.measured_offset_m = 0.001;
  idle(rig.node);  // holding its start position, read 1 mm off
  EXPECT_EQ(rig.node.latest_measurement().displacement_m[0], 0.001);
  EXPECT_EQ(rig.node.latest_measurement().force_n[1], 1e5 * 0.001);
  rig.actuator.measured_offset_m = 0.0;
  rig.actuator.script.push_back(servo::ActuatorStatus::kNoReply);
  idle(rig.node);  // no reply: the newest measurement stands
  EXPECT_EQ(rig.node.latest_measurement().displacement_m[0], 0.001);
  send(rig.node, command(0, {0.002, -0.003}));
  EXPECT_EQ(rig.node.latest_measurement().displacement_m[1], -0.003);
  EXPECT_EQ(rig.node.latest_measurement().force_n[0], 1e5 * 0.002);

  const double x0[] = {0.0, 0.0};
  rig.node.start(x0);  // a new start forgets it
  EXPECT_FALSE(rig.node.has_measurement());
}

TEST(ServoNodeController, StrokeClampGivesExactlyTheBound) {
  auto c = config();
  c.limits[0].max_stroke_m = 0.05;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  FeedbackSample out = send(node, command(1, {0.06}));
  EXPECT_EQ(actuator.last(), 0.05);
  EXPECT_EQ(out.limit_flags, transport::kLimitStroke);
  EXPECT_EQ(out.status, transport::kNodeLimitActive);
  send(node, command(2, {-0.07}));
  EXPECT_EQ(actuator.last(), -0.05);
  send(node, command(3, {0.01}));
  EXPECT_EQ(actuator.last(), 0.01);
  out = send(node, command(4, {0.08}));
  EXPECT_EQ(actuator.last(), 0.05);
  // Two activations (the limit acted on steps 1-2 and again on step 4), three ticks active.
  EXPECT_EQ(node.counters().activations(LimitKind::kStroke), 2u);
  EXPECT_EQ(node.counters().limit_active_ticks[static_cast<int>(LimitKind::kStroke)], 3u);
  ASSERT_EQ(node.events().size(), 2u);
  const LimitEvent& e = node.events()[0];
  EXPECT_EQ(e.tick, 0u);
  EXPECT_EQ(e.step, 1);
  EXPECT_EQ(e.channel, 0);
  EXPECT_EQ(e.kind, LimitKind::kStroke);
  EXPECT_EQ(e.action, LimitAction::kClamp);
  EXPECT_EQ(e.commanded_m, 0.06);
  EXPECT_EQ(e.applied_m, 0.05);
  EXPECT_EQ(e.observed, 0.06);
  EXPECT_EQ(e.bound, 0.05);
  EXPECT_EQ(node.events()[1].tick, 3u);
  EXPECT_FALSE(node.faulted());
}

TEST(ServoNodeController, StrokeHoldFreezesEveryChannelUntilAnInLimitCommand) {
  auto c = config(2);
  c.limits[0].max_stroke_m = 0.05;
  c.actions.stroke = LimitAction::kHold;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  send(node, command(1, {0.01, 0.02}));
  FeedbackSample out = send(node, command(2, {0.06, 0.03}));
  EXPECT_EQ(actuator.last(0), 0.01);
  EXPECT_EQ(actuator.last(1), 0.02);  // the in-limit channel is frozen too
  EXPECT_EQ(out.status, transport::kNodeLimitActive);
  EXPECT_EQ(out.step, 2);
  send(node, command(3, {0.055, 0.04}));
  EXPECT_EQ(actuator.last(0), 0.01);
  out = idle(node);  // no new command: still the out-of-limit one, still frozen
  EXPECT_EQ(actuator.last(0), 0.01);
  out = send(node, command(4, {0.045, 0.04}));
  EXPECT_EQ(actuator.last(0), 0.045);
  EXPECT_EQ(actuator.last(1), 0.04);
  EXPECT_EQ(out.status, transport::kNodeOk);
  EXPECT_FALSE(node.faulted());
  EXPECT_EQ(node.counters().activations(LimitKind::kStroke), 1u);
  ASSERT_EQ(node.events().size(), 1u);
  EXPECT_EQ(node.events()[0].applied_m, 0.01);
  EXPECT_EQ(node.events()[0].action, LimitAction::kHold);
}

TEST(ServoNodeController, StrokeAbortLatchesAFaultUntilRestart) {
  auto c = config();
  c.limits[0].max_stroke_m = 0.05;
  c.actions.stroke = LimitAction::kAbort;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  send(node, command(1, {0.02}));
  FeedbackSample out = send(node, command(2, {0.051}));
  EXPECT_EQ(actuator.last(), 0.02);
  EXPECT_TRUE(node.faulted());
  EXPECT_EQ(out.status, transport::kNodeFault | transport::kNodeLimitActive);
  EXPECT_EQ(out.limit_flags, transport::kLimitStroke);
  for (int step = 3; step < 20; ++step) {
    EXPECT_EQ(node.accept(command(step, {0.01})), CommandVerdict::kNotFollowing);
    node.tick(out);
    EXPECT_EQ(actuator.last(), 0.02);
    EXPECT_EQ(out.status, transport::kNodeFault);
  }
  EXPECT_EQ(node.counters().faults, 1u);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kNotFollowing), 17u);
  const double x0[] = {0.0};
  node.start(x0);
  EXPECT_FALSE(node.faulted());
  out = send(node, command(1, {0.01}));
  EXPECT_EQ(actuator.last(), 0.01);
  EXPECT_EQ(out.status, transport::kNodeOk);
}

TEST(ServoNodeController, VelocityClampGivesIncrementsOfExactlyVT) {
  auto c = config();
  c.limits[0].max_velocity_m_per_s = 0.125;  // v T = 2^-3 2^-10 = 2^-13 m
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  const double step_m = 0.125 * kPeriod, target = 0.01;
  // The coordinator keeps asking for 10 mm; 10 mm / 2^-13 m = 81.92 periods.
  int clamped_ticks = 0;
  for (int step = 1; step <= 100; ++step) {
    const double before = actuator.commands.empty() ? 0.0 : actuator.last();
    const FeedbackSample out = send(node, command(step, {target}));
    if (step <= 81) {
      ASSERT_EQ(actuator.last() - before, step_m) << step;
      ASSERT_EQ(out.limit_flags, transport::kLimitVelocity);
      ++clamped_ticks;
    } else {
      ASSERT_EQ(actuator.last(), target) << step;
      ASSERT_EQ(out.limit_flags, transport::kLimitNone) << step;
    }
  }
  EXPECT_EQ(clamped_ticks, 81);
  EXPECT_EQ(node.counters().activations(LimitKind::kVelocity), 1u);
  EXPECT_EQ(node.counters().limit_active_ticks[static_cast<int>(LimitKind::kVelocity)], 81u);
  EXPECT_EQ(node.events()[0].observed, target / kPeriod);
  EXPECT_EQ(node.events()[0].bound, 0.125);
}

TEST(ServoNodeController, IncrementClampAndTheTighterOfTheTwoRateLimits) {
  auto c = config(2);
  c.limits[0].max_increment_m = 0.00048828125;  // 2^-11 m
  c.limits[1].max_increment_m = 0.00048828125;
  c.limits[1].max_velocity_m_per_s = 0.125;  // 2^-13 m per period: tighter on channel 1
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  FeedbackSample out = send(node, command(1, {0.003, 0.003}));
  EXPECT_EQ(actuator.last(0), 0.00048828125);
  EXPECT_EQ(actuator.last(1), 0.0001220703125);
  EXPECT_EQ(out.limit_flags, transport::kLimitIncrement | transport::kLimitVelocity);
  for (int step = 2; step <= 6; ++step) send(node, command(step, {0.003, 0.003}));
  EXPECT_EQ(actuator.last(0), 6 * 0.00048828125);  // 6.144 increments to go: 6 full ones
  send(node, command(7, {0.003, 0.003}));
  EXPECT_EQ(actuator.last(0), 0.003);
  EXPECT_EQ(actuator.last(1), 7 * 0.0001220703125);
}

// The increment limit stated per second (max_increment_m_per_s) is the increment limit at the
// node's own rate: limit_to_envelope makes it v T, and it then clamps and aborts exactly as
// max_increment_m does, flagged as the increment (its action, not the velocity's).
TEST(ServoNodeController, AnIncrementPerSecondActsAsTheIncrementAtTheNodesOwnRate) {
  for (const double rate_hz : {1024.0, 2048.0, 4096.0}) {
    auto c = config();
    c.control_period_s = 1.0 / rate_hz;
    c.limits[0].max_increment_m_per_s = 0.5;  // 2^-1 m/s: 2^-11, 2^-12, 2^-13 m per period
    limit_to_envelope(c, servo::Envelope{0.127, 156.0e3, 1.31});
    const double increment_m = 0.5 / rate_hz;
    EXPECT_EQ(c.limits[0].max_increment_m, increment_m) << rate_hz;
    {
      NodeRig rig(c);
      auto& [actuator, node] = rig;
      // 1 m/s asked: beyond the increment, within the rig's velocity capacity (1.31 m/s).
      const FeedbackSample out = send(node, command(1, {1.0 / rate_hz}));
      EXPECT_EQ(actuator.last(), increment_m) << rate_hz;
      EXPECT_EQ(out.limit_flags, transport::kLimitIncrement) << rate_hz;
      EXPECT_EQ(node.events()[0].bound, increment_m) << rate_hz;
      send(node, command(2, {2.0 * increment_m}));  // within one period's reach: applied as sent
      EXPECT_EQ(actuator.last(), 2.0 * increment_m) << rate_hz;
    }
    c.actions.increment = LimitAction::kAbort;
    NodeRig rig(c);
    auto& [actuator, node] = rig;
    send(node, command(1, {increment_m}));
    const FeedbackSample out = send(node, command(2, {3.5 * increment_m}));
    EXPECT_EQ(actuator.last(), increment_m) << rate_hz;
    EXPECT_TRUE(node.faulted()) << rate_hz;
    EXPECT_EQ(out.limit_flags, transport::kLimitIncrement) << rate_hz;
  }
}

TEST(ServoNodeController, VelocityHoldAndIncrementAbort) {
  {
    auto c = config();
    c.limits[0].max_velocity_m_per_s = 1.0;  // ~0.98 mm per period
    c.actions.velocity = LimitAction::kHold;
    NodeRig rig(c);
    auto& [actuator, node] = rig;
    FeedbackSample out = send(node, command(1, {0.002}));
    EXPECT_EQ(actuator.last(), 0.0);
    EXPECT_EQ(out.status, transport::kNodeLimitActive);
    send(node, command(2, {0.0005}));  // back within one period's reach of the frozen command
    EXPECT_EQ(actuator.last(), 0.0005);
    EXPECT_FALSE(node.faulted());
  }
  {
    auto c = config();
    c.limits[0].max_increment_m = 0.001;
    c.actions.increment = LimitAction::kAbort;
    NodeRig rig(c);
    auto& [actuator, node] = rig;
    send(node, command(1, {0.0009}));
    const FeedbackSample out = send(node, command(2, {0.0021}));
    EXPECT_EQ(actuator.last(), 0.0009);
    EXPECT_TRUE(node.faulted());
    EXPECT_EQ(out.limit_flags, transport::kLimitIncrement);
    EXPECT_EQ(node.events()[0].action, LimitAction::kAbort);
  }
}

// Ideal actuator on a 1 MN/m specimen, commands rising 1 mm per step, force limit 5.5 kN:
// the load cell reads 6 kN after step 6, so the limit acts on the tick of step 7.
ServoNodeConfig force_config(LimitAction action) {
  auto c = config();
  c.limits[0].max_force_n = 5500.0;
  c.actions.force = action;
  return c;
}

TEST(ServoNodeController, ForceAbortLatchesOnTheTickAfterTheMeasurement) {
  NodeRig rig(force_config(LimitAction::kAbort), 1e6);
  auto& [actuator, node] = rig;
  FeedbackSample out;
  for (int step = 1; step <= 6; ++step) {
    out = send(node, command(step, {step * 1e-3}));
    ASSERT_EQ(out.status, transport::kNodeOk) << step;
  }
  EXPECT_EQ(out.force_n[0], 6000.0);
  out = send(node, command(7, {7e-3}));
  EXPECT_EQ(actuator.last(), 6e-3);
  EXPECT_EQ(out.status, transport::kNodeFault | transport::kNodeLimitActive);
  EXPECT_EQ(out.limit_flags, transport::kLimitForce);
  EXPECT_EQ(node.accept(command(8, {5e-3})), CommandVerdict::kNotFollowing);
  node.tick(out);
  EXPECT_EQ(actuator.last(), 6e-3);
  ASSERT_EQ(node.events().size(), 1u);
  EXPECT_EQ(node.events()[0].tick, 6u);
  EXPECT_EQ(node.events()[0].step, 7);
  EXPECT_EQ(node.events()[0].observed, 6000.0);
  EXPECT_EQ(node.events()[0].bound, 5500.0);
}

TEST(ServoNodeController, ForceClampStopsLoadingFurtherButAllowsUnloading) {
  NodeRig rig(force_config(LimitAction::kClamp), 1e6);
  auto& [actuator, node] = rig;
  for (int step = 1; step <= 6; ++step) send(node, command(step, {step * 1e-3}));
  for (int step = 7; step <= 10; ++step) {
    const FeedbackSample out = send(node, command(step, {step * 1e-3}));
    EXPECT_EQ(actuator.last(), 6e-3) << step;
    EXPECT_EQ(out.limit_flags, transport::kLimitForce);
  }
  const FeedbackSample out = send(node, command(11, {4e-3}));
  EXPECT_EQ(actuator.last(), 4e-3);
  EXPECT_EQ(out.limit_flags, transport::kLimitForce);  // it acted on this tick (6 kN measured before it)
  EXPECT_EQ(send(node, command(12, {4.5e-3})).limit_flags, transport::kLimitNone);
  EXPECT_FALSE(node.faulted());
  EXPECT_EQ(node.counters().activations(LimitKind::kForce), 1u);
}

TEST(ServoNodeController, ForceHoldFreezesTheCommandWhileTheForceIsExceeded) {
  NodeRig rig(force_config(LimitAction::kHold), 1e6);
  auto& [actuator, node] = rig;
  for (int step = 1; step <= 6; ++step) send(node, command(step, {step * 1e-3}));
  for (int step = 7; step <= 12; ++step) {
    const FeedbackSample out = send(node, command(step, {(14 - step) * 1e-3}));
    EXPECT_EQ(actuator.last(), 6e-3) << step;  // frozen whatever the command
    EXPECT_EQ(out.status, transport::kNodeLimitActive);
  }
  EXPECT_FALSE(node.faulted());
}

TEST(ServoNodeController, WatchdogHoldsAfterExactlyNMissingPeriods) {
  auto c = config();
  c.command_timeout_periods = 5;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  for (int step = 1; step <= 10; ++step) send(node, command(step, {step * 1e-4}));
  for (int missing = 1; missing <= 4; ++missing) {
    const FeedbackSample out = idle(node);
    EXPECT_EQ(out.status, transport::kNodeOk) << missing;
    EXPECT_FALSE(node.holding());
  }
  FeedbackSample out = idle(node);  // the fifth missing period
  EXPECT_EQ(out.status, transport::kNodeHolding);
  EXPECT_EQ(out.step, 10);
  for (int missing = 6; missing <= 40; ++missing) {
    out = idle(node);
    EXPECT_EQ(actuator.last(), 1e-3);  // holds the last command
    EXPECT_EQ(out.status, transport::kNodeHolding);
  }
  EXPECT_EQ(node.counters().holds, 1u);
  EXPECT_EQ(node.counters().missed_periods, 40u);
  out = send(node, command(11, {1.1e-3}));  // commands resume: so does the node
  EXPECT_EQ(out.status, transport::kNodeOk);
  EXPECT_EQ(actuator.last(), 1.1e-3);
  EXPECT_FALSE(node.holding());
}

TEST(ServoNodeController, RampToSafeReachesTheSafePositionAtTheConfiguredRate) {
  auto c = config(2);
  c.command_timeout_periods = 3;
  c.on_command_loss = LossAction::kRampToSafe;
  c.safe_ramp_velocity_m_per_s = 0.0625;   // 2^-4 m/s: 2^-14 m per period
  c.safe_position_m = {0.0, 0.001953125};  // channel 1 already there (2^-9 m)
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  // 2^-7 + 2^-16 m from safe: 128.25 ramp periods, so 129 ticks, the last one partial.
  const double start_m = 0.0078125 + 0.0000152587890625, step_m = 0.0625 * kPeriod;
  send(node, command(1, {start_m, 0.001953125}));
  idle(node);
  idle(node);
  for (int k = 1; k <= 128; ++k) {
    const FeedbackSample out = idle(node);  // the first of these is the third missing period
    ASSERT_EQ(actuator.last(0), start_m - k * step_m) << k;
    ASSERT_EQ(actuator.last(1), 0.001953125);
    ASSERT_EQ(out.status, transport::kNodeHolding);
  }
  idle(node);
  EXPECT_EQ(actuator.last(0), 0.0);  // arrived after ceil(d / (v T)) = 129 periods
  EXPECT_DOUBLE_EQ(129 * kPeriod, std::ceil((start_m - 0.0) / 0.0625 / kPeriod) * kPeriod);
  for (int i = 0; i < 20; ++i) idle(node);
  EXPECT_EQ(actuator.last(0), 0.0);
  // The safe state is final: the node follows nothing until restarted.
  EXPECT_EQ(node.accept(command(2, {0.001, 0.0})), CommandVerdict::kNotFollowing);
  EXPECT_EQ(idle(node).status, transport::kNodeHolding);
  EXPECT_TRUE(node.in_safe_state());
  EXPECT_EQ(node.counters().limit_activations, (std::array<std::uint64_t, kLimitKinds>{}));  // within every limit
}

// Several channels ramp to safe along one straight line and arrive together, the farthest at
// the safe velocity: channel 1, half as far from safe as channel 0, moves half as fast, so a
// specimen driven through a setup goes back along a straight path, not one actuator first.
TEST(ServoNodeController, RampToSafeMovesEveryChannelAlongOneStraightLine) {
  auto c = config(2);
  c.command_timeout_periods = 3;
  c.on_command_loss = LossAction::kRampToSafe;
  c.safe_ramp_velocity_m_per_s = 0.0625;  // 2^-14 m per period
  c.safe_position_m = {0.0, 0.001};
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  const double start0_m = 0.0078125, start1_m = 0.001 - 0.00390625, step_m = 0.0625 * kPeriod;  // 2^-7, -2^-8
  send(node, command(1, {start0_m, start1_m}));
  idle(node);
  idle(node);
  for (int k = 1; k <= 128; ++k) {
    idle(node);
    ASSERT_EQ(actuator.last(0), start0_m - k * step_m) << k;
    ASSERT_NEAR(actuator.last(1), start1_m + k * step_m / 2, 1e-15) << k;
  }
  EXPECT_EQ(actuator.last(0), 0.0);
  EXPECT_NEAR(actuator.last(1), 0.001, 1e-15);  // together, after 128 periods
  idle(node);
  EXPECT_EQ(actuator.last(1), 0.001);
}

TEST(ServoNodeController, BadCommandsAreDroppedCountedAndNeverApplied) {
  IdealActuator actuator(2);
  auto c = config(2);
  c.command_timeout_periods = 2;
  ServoNodeController node(c, actuator);
  const double x0[] = {0.001, 0.002};
  node.start(x0);
  send(node, command(2, {0.001, 0.002}));

  auto wrong_test = command(3, {0.01, 0.01});
  wrong_test.test_id = kTest + 1;
  auto wrong_site = command(3, {0.01, 0.01});
  wrong_site.site_id = kSite + 1;
  auto nan = command(3, {0.01, std::nan("")});
  auto infinite_time = command(3, {0.01, 0.01});
  infinite_time.time_s = std::numeric_limits<double>::infinity();
  EXPECT_EQ(node.accept(wrong_test), CommandVerdict::kWrongTestId);
  EXPECT_EQ(node.accept(wrong_site), CommandVerdict::kWrongSiteId);
  EXPECT_EQ(node.accept(command(3, {0.01})), CommandVerdict::kWrongChannelCount);
  EXPECT_EQ(node.accept(command(3, {0.01, 0.01, 0.01})), CommandVerdict::kWrongChannelCount);
  EXPECT_EQ(node.accept(nan), CommandVerdict::kNonFinite);
  EXPECT_EQ(node.accept(infinite_time), CommandVerdict::kNonFinite);
  EXPECT_EQ(node.accept(command(2, {0.01, 0.01})), CommandVerdict::kNotNewer);  // duplicate
  EXPECT_EQ(node.accept(command(1, {0.01, 0.01})), CommandVerdict::kNotNewer);  // out of order
  EXPECT_EQ(node.accept(command(-1, {0.01, 0.01})), CommandVerdict::kNotNewer);
  for (int i = 0; i < 10; ++i) {
    const FeedbackSample out = idle(node);
    EXPECT_EQ(out.step, 2);
  }
  for (const auto& sent : actuator.commands) EXPECT_EQ(sent, std::vector<double>({0.001, 0.002}));
  const ServoNodeCounters& n = node.counters();
  EXPECT_EQ(n.dropped(CommandVerdict::kWrongTestId), 1u);
  EXPECT_EQ(n.dropped(CommandVerdict::kWrongSiteId), 1u);
  EXPECT_EQ(n.dropped(CommandVerdict::kWrongChannelCount), 2u);
  EXPECT_EQ(n.dropped(CommandVerdict::kNonFinite), 2u);
  EXPECT_EQ(n.dropped(CommandVerdict::kNotNewer), 3u);
  EXPECT_EQ(n.dropped_total(), 9u);
  EXPECT_EQ(n.accepted, 1u);
  EXPECT_TRUE(node.holding());  // dropped commands do not feed the watchdog

  // A NaN in a slot beyond the node's channels is not part of the command.
  auto padded = command(3, {0.0011, 0.0021});
  padded.displacement_m[5] = std::nan("");
  EXPECT_EQ(node.accept(padded), CommandVerdict::kAccepted);
}

// A node restarted while its test carries on (the coordinator tolerating that many late
// periods) sees the test first at a step far beyond 0. Its actuator starts at the node's own
// initial position, not where the test had put the specimen: it must not take the test over.
TEST(ServoNodeController, ANodeThatMissedTheStartOfATestNeverFollowsIt) {
  IdealActuator actuator(1);
  auto c = config();
  c.command_timeout_periods = 4;
  ServoNodeController node(c, actuator);
  const double x0[] = {0.0};
  node.start(x0);
  for (int step = 1186; step < 1200; ++step) {
    EXPECT_EQ(node.accept(command(step, {0.004})), CommandVerdict::kJoinedMidTest);
    const FeedbackSample out = idle(node);
    EXPECT_EQ(out.step, -1);
    EXPECT_EQ(out.displacement_m[0], 0.0);
  }
  for (const auto& sent : actuator.commands) EXPECT_EQ(sent, std::vector<double>({0.0}));
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kJoinedMidTest), 14u);
  EXPECT_EQ(node.counters().accepted, 0u);
  EXPECT_FALSE(node.holding());  // nothing to hold after: the node still waits for a test
  EXPECT_STREQ(command_verdict_name(CommandVerdict::kJoinedMidTest), "joined mid-test");

  // A node there from the start may miss the first commands, up to its watchdog's reach.
  node.start(x0);
  EXPECT_EQ(node.accept(command(4, {0.001})), CommandVerdict::kAccepted);
  EXPECT_EQ(idle(node).step, 4);
  // Later steps: newer, and no further ahead than a coordinator at this rate can have gone
  // (one step a tick since, plus a second's worth: ServoNodeController's max_step_lead_).
  EXPECT_EQ(node.accept(command(1000, {0.001})), CommandVerdict::kAccepted);
}

TEST(ServoNodeController, TheNewestPendingCommandWins) {
  auto c = config();
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  EXPECT_EQ(node.accept(command(1, {0.001})), CommandVerdict::kAccepted);
  EXPECT_EQ(node.accept(command(2, {0.002})), CommandVerdict::kAccepted);
  EXPECT_EQ(node.accept(command(1, {0.003})), CommandVerdict::kNotNewer);
  const FeedbackSample out = idle(node);
  EXPECT_EQ(actuator.last(), 0.002);
  EXPECT_EQ(out.step, 2);
  EXPECT_EQ(node.counters().superseded, 1u);
  EXPECT_EQ(node.counters().applied, 1u);
  EXPECT_EQ(actuator.commands.size(), 1u);
}

TEST(ServoNodeController, ActuatorNoReplyKeepsTheLastMeasurementAndAFaultLatches) {
  auto c = config();
  NodeRig rig(c, 1e5);
  auto& [actuator, node] = rig;
  send(node, command(1, {0.001}));
  actuator.script = {servo::ActuatorStatus::kNoReply};
  FeedbackSample out = send(node, command(2, {0.002}));
  EXPECT_EQ(out.displacement_m[0], 0.001);  // the last measurement, not the new command
  EXPECT_EQ(out.force_n[0], 100.0);
  EXPECT_EQ(out.step, 2);
  EXPECT_EQ(out.status, transport::kNodeOk);
  EXPECT_FALSE(node.reading().fresh);
  EXPECT_EQ(node.counters().actuator_no_replies, 1u);
  actuator.script = {servo::ActuatorStatus::kFault};
  out = send(node, command(3, {0.003}));
  EXPECT_EQ(out.status, transport::kNodeFault);
  EXPECT_TRUE(node.faulted());
  EXPECT_EQ(node.accept(command(4, {0.004})), CommandVerdict::kNotFollowing);
  idle(node);
  EXPECT_EQ(actuator.last(), 0.003);  // the command it had when the fault came, held
  EXPECT_EQ(node.counters().actuator_faults, 1u);
  EXPECT_EQ(node.counters().faults, 1u);
}

// What latched the fault travels in the node's heartbeat: the actuator's own words (a lab
// controller's refusal), the first ones only; or the measurement that faulted the node.
TEST(ServoNodeController, KeepsWhatFaultedItTheActuatorsWordsOrTheMeasurement) {
  auto c = config();
  {
    NodeRig rig(c);
    auto& [actuator, node] = rig;
    send(node, command(1, {0.001}));
    EXPECT_EQ(std::string(node.fault_text().data()), "");
    actuator.fault_words = "ERROR\tproposal refused: x displacement beyond the site's limit";
    actuator.script = {servo::ActuatorStatus::kFault};
    send(node, command(2, {0.002}));
    actuator.fault_words = "a later word";
    actuator.script = {servo::ActuatorStatus::kFault};
    idle(node);
    EXPECT_EQ(std::string(node.fault_text().data()), "ERROR\tproposal refused: x displacement beyond the site's limit");
    node.start(std::array{0.0});
    EXPECT_EQ(std::string(node.fault_text().data()), "");
  }
  limit_to_envelope(c, {0.0625, 2048.0, 100.0});
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  actuator.measured_offset_m = 0.0625;
  send(node, command(1, {0.0}));
  ASSERT_TRUE(node.faulted());
  EXPECT_EQ(std::string(node.fault_text().data()), "stroke rig_envelope on channel 0: 0.0625 beyond 0.0625");
}

TEST(ServoNodeController, TheEventLogKeepsTheFirstActivationsAndCountsTheRest) {
  auto c = config();
  c.limits[0].max_stroke_m = 0.05;
  c.event_log_capacity = 2;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  for (int step = 1; step <= 8; ++step) send(node, command(step, {step % 2 ? 0.06 : 0.0}));
  EXPECT_EQ(node.counters().activations(LimitKind::kStroke), 4u);
  ASSERT_EQ(node.events().size(), 2u);
  EXPECT_EQ(node.events()[1].step, 3);
  EXPECT_EQ(node.events_not_logged(), 2u);
}

TEST(ServoNodeController, StartRefusesAnInitialPositionBeyondTheStroke) {
  IdealActuator actuator(1);
  auto c = config();
  c.limits[0].max_stroke_m = 0.05;
  ServoNodeController node(c, actuator);
  const double beyond[] = {0.051}, two[] = {0.0, 0.0};
  EXPECT_THROW(node.start(beyond), std::invalid_argument);
  EXPECT_THROW(node.start(two), std::invalid_argument);
  EXPECT_TRUE(actuator.started_at.empty());
}

// The interlocks act on what is measured: a piston that drifts beyond the stroke while its
// command stays inside (a servovalve fault, a lost LVDT) trips the stroke limit.
TEST(ServoNodeController, AMeasuredDisplacementBeyondTheStrokeTripsItsLimit) {
  auto c = config();
  c.limits[0].max_stroke_m = 0.05;
  c.actions.stroke = LimitAction::kAbort;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  send(node, command(1, {0.01}));
  EXPECT_FALSE(node.faulted());
  actuator.measured_offset_m = 0.045;  // measured 0.055 for a command of 0.01
  send(node, command(2, {0.01}));      // the exchange that measures it
  const FeedbackSample out = send(node, command(3, {0.01}));
  EXPECT_TRUE(node.faulted());
  EXPECT_NE(out.status & transport::kNodeFault, 0u);
  EXPECT_NE(out.limit_flags & transport::kLimitStroke, 0u);
  ASSERT_EQ(node.events().size(), 1u);
  EXPECT_EQ(node.events()[0].kind, LimitKind::kStroke);
  EXPECT_DOUBLE_EQ(node.events()[0].observed, 0.055);  // the measurement, not the command
}

// A limit whose action is ramp_to_safe moves every channel to its safe position at the safe
// ramp velocity, exactly v T per period, and the node then follows no command.
TEST(ServoNodeController, RampToSafeOnALimitGoesToTheSafePositionAtTheSafeVelocity) {
  auto c = config();
  c.limits[0].max_stroke_m = 0.05;
  c.actions.stroke = LimitAction::kRampToSafe;
  c.safe_ramp_velocity_m_per_s = 0.0625;  // 2^-14 m per period
  c.safe_position_m = {0.0};
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  const double start_m = 0.0078125, step_m = 0.0625 * kPeriod;  // 2^-7 m: 128 periods from safe
  send(node, command(1, {start_m}));
  const FeedbackSample tripped = send(node, command(2, {0.06}));
  EXPECT_NE(tripped.limit_flags & transport::kLimitStroke, 0u);
  EXPECT_EQ(actuator.last(), start_m);  // the trip stops the command where it is
  for (int k = 1; k <= 128; ++k) {
    idle(node);
    ASSERT_EQ(actuator.last(), start_m - k * step_m) << k;
  }
  for (int i = 0; i < 10; ++i) idle(node);
  EXPECT_EQ(actuator.last(), 0.0);
  EXPECT_EQ(node.accept(command(3, {0.01})), CommandVerdict::kNotFollowing);
  EXPECT_FALSE(node.faulted());
}

// A hold stops a moving command at the stop deceleration instead of freezing it: a stop from
// v takes v / (a T) periods, and the command comes to rest v^2 / (2 a) further on.
TEST(ServoNodeController, AHoldBrakesAtTheStopDeceleration) {
  auto c = config();
  c.limits[0].max_velocity_m_per_s = 0.1;
  c.actions.velocity = LimitAction::kHold;
  const double a = 2.0, v = 0.05;
  c.limits[0].stop_deceleration_m_per_s2 = a;
  NodeRig rig(c);
  auto& [actuator, node] = rig;
  std::int64_t step = 1;
  double x = 0.0;
  for (; step <= 100; ++step) send(node, command(step, {x += v * kPeriod}));  // a steady 0.05 m/s
  const double moving_at_m = actuator.last();
  std::vector<double> applied{actuator.last()};
  for (int k = 0; k < 100; ++k) {
    send(node, command(step++, {x += 0.2 * kPeriod}));  // now twice the velocity limit
    applied.push_back(actuator.last());
  }
  EXPECT_GT(node.counters().activations(LimitKind::kVelocity), 0u);
  double v_before = v, max_dv = 0.0;
  int moving = 0;
  for (std::size_t i = 1; i < applied.size(); ++i) {
    const double v_now = (applied[i] - applied[i - 1]) / kPeriod;
    max_dv = std::max(max_dv, std::abs(v_now - v_before));
    moving += v_now > 0.0 ? 1 : 0;
    v_before = v_now;
  }
  EXPECT_LE(max_dv, a * kPeriod * (1 + 1e-9));             // no period changes the velocity by more than a T
  EXPECT_NEAR(moving, v / (a * kPeriod), 1.0);             // 25.6 periods to stop
  EXPECT_EQ(applied.back(), applied[applied.size() - 2]);  // at rest
  EXPECT_NEAR(applied.back() - moving_at_m, v * v / (2 * a), v * kPeriod);  // 0.625 mm on
}

// A command racing at the stroke brakes at the stop deceleration and comes to rest on it, in
// either direction: it moves at v until v^2 / (2 a) short of the stroke, no period changes its
// velocity by more than a T until the one that lands it on the stroke, and it never passes it. Moving away from the
// stroke it is close to, it is not braked at all (only the bound ahead of it can slow it).
TEST(ServoNodeController, ACommandRacingAtTheStrokeBrakesOnlyTowardIt) {
  for (const double sign : {1.0, -1.0}) {
    auto c = config();
    const double stroke = 0.05, a = 2.0, v = 0.2;  // braking distance v^2 / (2 a) = 10 mm
    c.limits[0].max_stroke_m = stroke;
    c.limits[0].stop_deceleration_m_per_s2 = a;
    c.actions.stroke = LimitAction::kClamp;
    NodeRig rig(c);
    auto& [actuator, node] = rig;
    std::vector<double> applied{0.0};
    std::int64_t step = 1;
    double x = 0.0;
    for (; step <= 400; ++step) {  // 78 mm asked for: beyond the stroke
      send(node, command(step, {sign * (x += v * kPeriod)}));
      applied.push_back(sign * actuator.last());
    }
    double peak = 0.0;
    int braking_from = -1;
    for (std::size_t i = 1; i < applied.size(); ++i) {
      const double v_now = (applied[i] - applied[i - 1]) / kPeriod;
      if (braking_from < 0 && v_now < v * (1 - 1e-9)) braking_from = static_cast<int>(i);
      peak = std::max(peak, applied[i]);
    }
    EXPECT_LE(peak, stroke) << sign;
    EXPECT_NEAR(applied.back(), stroke, 1e-6) << sign;  // at rest on the stroke
    ASSERT_GT(braking_from, 1) << sign;
    EXPECT_NEAR(applied[braking_from - 1], stroke - v * v / (2 * a), 2 * v * kPeriod) << sign;
    // Up to the period that lands it on the stroke (that one stops the rest of the way: within
    // a T of the discrete profile's last speed).
    for (std::size_t i = static_cast<std::size_t>(braking_from) + 1; i < applied.size() && applied[i] < stroke; ++i) {
      const double dv = std::abs((applied[i] - applied[i - 1]) - (applied[i - 1] - applied[i - 2])) / kPeriod;
      ASSERT_LE(dv, a * kPeriod * (1 + 1e-9)) << sign << " period " << i;
    }
    // Now away from the stroke at v: every command followed exactly from the first period on.
    for (int k = 1; k <= 20; ++k) {
      send(node, command(step++, {sign * (stroke - k * v * kPeriod)}));
      ASSERT_EQ(actuator.last(), sign * (stroke - k * v * kPeriod)) << sign << " " << k;
    }
  }
}

// What no measurement may reach, whatever the limits' actions (ServoNodeConfig::rails, rig):
// a reading on an A/D converter's rail may stand for any value beyond it, and the node faults
// on the tick that brings it, the event saying which rail. Here the stroke limit would only
// clamp and the force limit only hold.
TEST(ServoNodeController, AReadingOnAConverterRailFaultsTheNodeWhateverTheLimitsAction) {
  for (const bool force : {false, true}) {
    auto c = config();
    c.actions.stroke = LimitAction::kClamp;
    c.actions.force = LimitAction::kHold;
    servo::SignalConverterParameters adc;  // +/-1 V, 10 bits, 0.01 m/V or 1000 N/V
    adc.units_per_volt = force ? 1000.0 : 0.01;
    adc.saturation_v = 1.0;
    adc.bits = 10;
    servo::ReadingRanges rails;
    (force ? rails.force_n : rails.displacement_m) = adc.range();
    read_through_converters(c, rails);
    const double rail = adc.range().high;  // 511 steps of 2/1024 V: 0.998 V
    ASSERT_DOUBLE_EQ(rail, (force ? 1000.0 : 0.01) * 511.0 * 2.0 / 1024.0);
    const double to_rail_m = rail;  // 1 N/m on the load cell: the force reads x
    NodeRig rig(c, 1.0);
    auto& [actuator, node] = rig;
    FeedbackSample out = send(node, command(1, {0.5 * to_rail_m}));
    EXPECT_EQ(out.status, transport::kNodeOk) << force;
    out = send(node, command(2, {to_rail_m}));  // the reading is the rail's: beyond any limit
    EXPECT_TRUE(node.faulted()) << force;
    EXPECT_EQ(out.status, transport::kNodeFault | transport::kNodeLimitActive) << force;
    EXPECT_EQ(out.limit_flags, force ? transport::kLimitForce : transport::kLimitStroke);
    ASSERT_EQ(node.events().size(), 1u);
    const LimitEvent& e = node.events()[0];
    EXPECT_EQ(e.cause, LimitCause::kConverterRail);
    EXPECT_EQ(e.kind, force ? LimitKind::kForce : LimitKind::kStroke);
    EXPECT_EQ(e.action, LimitAction::kAbort);
    EXPECT_EQ(e.bound, rail);
    EXPECT_EQ(e.tick, 1u);
    EXPECT_EQ(node.counters().faults, 1u);
    EXPECT_EQ(node.accept(command(3, {0.0})), CommandVerdict::kNotFollowing);
    // The negative rail alike, one code further out (-512 steps: two's complement): the
    // negative of the positive rail is still a reading.
    NodeRig other(c, 1.0);
    EXPECT_EQ(send(other.node, command(1, {-rail})).status, transport::kNodeOk) << force;
    out = send(other.node, command(2, {adc.range().low}));
    EXPECT_TRUE(other.node.faulted()) << force;
    ASSERT_EQ(other.node.events().size(), 1u);
    EXPECT_EQ(other.node.events()[0].bound, -adc.range().low);
    EXPECT_EQ(other.node.events()[0].observed, -adc.range().low);
  }
}

// A piston measured at the rig's stroke (its end stop) or a load cell at the rig's force
// capacity faults the node, whatever sent the measurement and whatever the limits' actions:
// here the command stays inside the stroke while the piston drifts onto the end stop.
TEST(ServoNodeController, AMeasurementAtOrBeyondTheRigsEnvelopeFaultsTheNode) {
  auto c = config();
  c.actions.force = LimitAction::kClamp;
  limit_to_envelope(c, {0.0625, 2048.0, 100.0});
  {
    NodeRig rig(c);
    auto& [actuator, node] = rig;
    send(node, command(1, {0.03125}));
    actuator.measured_offset_m = 0.03125;  // measured exactly 0.0625: not beyond the stroke limit
    const FeedbackSample out = send(node, command(2, {0.03125}));
    EXPECT_TRUE(node.faulted());
    EXPECT_EQ(out.status, transport::kNodeFault | transport::kNodeLimitActive);
    EXPECT_EQ(out.limit_flags, transport::kLimitStroke);
    ASSERT_EQ(node.events().size(), 1u);
    EXPECT_EQ(node.events()[0].cause, LimitCause::kRigEnvelope);
    EXPECT_EQ(node.events()[0].observed, 0.0625);
    EXPECT_EQ(node.events()[0].bound, 0.0625);
  }
  {
    NodeRig rig(c, 65536.0);  // 0.03125 m reads 2048 N, the rig's force capacity
    auto& [actuator, node] = rig;
    FeedbackSample out = send(node, command(1, {0.03}));
    EXPECT_FALSE(node.faulted());
    out = send(node, command(2, {0.03125}));
    EXPECT_TRUE(node.faulted());
    EXPECT_EQ(out.limit_flags & transport::kLimitForce, transport::kLimitForce);
    ASSERT_FALSE(node.events().empty());
    EXPECT_EQ(node.events().back().cause, LimitCause::kRigEnvelope);
    EXPECT_EQ(node.events().back().kind, LimitKind::kForce);
  }
}

// The same through the UDP hardware adapter: an emulated controller whose actuator reads 1.1
// times its command (a miscalibrated servo loop) drives the piston onto its 50 mm end stop for
// a command of 47.5 mm, inside every limit. The protocol carries no end-stop flag; the
// measurement alone faults the node.
// That plant: 1.1 times its command, a 50 mm stroke.
servo::TransferFunctionPlantParameters overshooting_plant() {
  servo::TransferFunctionPlantParameters p;
  p.transfer_function = {servo::Polynomial{1100.0}, servo::Polynomial{1000.0, 1.0}};
  p.rig = {0.05, 1e6, 100.0};
  return p;
}

ServoNodeConfig end_stop_config() {
  auto c = config();
  limit_to_envelope(c, overshooting_plant().rig);
  return c;
}

// Starts the node and commands it 47.5 mm until it faults (at most 400 periods); the last
// feedback.
FeedbackSample drive_to_the_end_stop(ServoNodeController& node) {
  node.start(std::vector<double>{0.0});
  FeedbackSample out;
  for (std::int64_t step = 1; step <= 400 && !node.faulted(); ++step) out = send(node, command(step, {0.0475}));
  return out;
}

void expect_faulted_on_the_rigs_stroke(const ServoNodeController& node, const FeedbackSample& out) {
  ASSERT_TRUE(node.faulted()) << out.displacement_m[0];
  EXPECT_NEAR(out.displacement_m[0], 0.05, 1e-12);  // exactly over UDP; through %.10E for the plugin
  EXPECT_NE(out.status & transport::kNodeFault, 0u);
  EXPECT_EQ(node.counters().activations(LimitKind::kStroke), 1u);
  ASSERT_EQ(node.events().size(), 1u);
  EXPECT_EQ(node.events()[0].cause, LimitCause::kRigEnvelope);
  for (const auto& command_m : node.command_m()) EXPECT_LE(command_m, 0.0475);  // never beyond its command
}

TEST(ServoNodeController, AMeasurementAtTheRigsStrokeFromTheUdpAdapterFaultsTheNode) {
  servo::TransferFunctionPlant plant(overshooting_plant());
  servo::Plant* plants[] = {&plant};
  ControllerEmulator emulator(plants, testing::emulator_config());
  emulator.start(std::vector<double>{0.0});
  UdpControllerActuator actuator(testing::adapter_config(emulator, 1));
  testing::pair(emulator, actuator);
  const testing::Serving serving(emulator);
  ServoNodeController node(end_stop_config(), actuator);
  expect_faulted_on_the_rigs_stroke(node, drive_to_the_end_stop(node));
}

// The same from a NEES plugin site, whose protocol carries no end-stop flag either.
TEST(ServoNodeController, AMeasurementAtTheRigsStrokeFromThePluginAdapterFaultsTheNode) {
  servo::TransferFunctionPlant plant(overshooting_plant());
  servo::Plant* plants[] = {&plant};
  PluginSiteConfig site_config;
  site_config.step_duration_s = 1.0 / 1024.0;
  site_config.control_points = {{"MDL-00-01", {{"x", "translation", -1.0, 1.0, 1.0, 1.0}}}};
  PluginSiteEmulator site(plants, site_config);
  site.start(std::vector<double>{0.0});
  const testing::ServingSite serving(site);
  NeesPluginActuator actuator(testing::plugin_adapter_config(
      site, {{"MDL-00-01", nees_plugin::Axis::kX, nees_plugin::Motion::kTranslation, 1.0, 1.0}}));
  ServoNodeController node(end_stop_config(), actuator);
  expect_faulted_on_the_rigs_stroke(node, drive_to_the_end_stop(node));
  EXPECT_EQ(actuator.failed_side(), "none");  // the link is whole: the node faulted on what it read
}

namespace run_identity {

constexpr std::uint64_t kOtherRun = 0xb0b, kWriter = 7, kOtherWriter = 8;

// A command of run `run` from writer `writer` (the node's endpoint fills the writer in).
CommandSample of(std::uint64_t run, std::uint64_t writer, std::int64_t step, double x_m) {
  CommandSample c = command(step, {x_m});
  c.run_id = run;
  c.writer = writer;
  return c;
}

CommandSample end_of(std::uint64_t run, std::uint64_t writer, std::int64_t step) {
  CommandSample c = of(run, writer, step, 0.0);
  c.end_of_run = true;
  return c;
}

struct NodeServingRun : ::testing::Test {
  NodeServingRun() : rig(config()) {}
  NodeRig rig;
  ServoNodeController& node = rig.node;
  IdealActuator& actuator = rig.actuator;
};

// Two coordinators of one test id: the node serves the run it saw first, refuses the other's
// commands (never applied), and says in every feedback sample which run it serves, so that the
// other coordinator never takes these measurements for its own.
TEST_F(NodeServingRun, ServesTheFirstRunItSeesAndRefusesAnother) {
  EXPECT_EQ(node.serving_run(), 0u);
  EXPECT_EQ(idle(node).run_id, 0u);  // serving no run: no coordinator may use this sample
  FeedbackSample out = send(node, of(kRun, kWriter, 0, 0.001));
  EXPECT_EQ(node.serving_run(), kRun);
  EXPECT_EQ(out.run_id, kRun);
  for (std::int64_t step = 0; step < 5; ++step) {
    // The other run's command, of the same test and site, even with a newer step.
    EXPECT_EQ(node.accept(of(kOtherRun, 9, step + 1, 0.02)), CommandVerdict::kOtherRun);
    out = send(node, of(kRun, kWriter, step + 1, 0.001 * static_cast<double>(step + 2)));
    EXPECT_EQ(out.run_id, kRun);
    EXPECT_EQ(out.step, step + 1);
  }
  for (const auto& sent : actuator.commands) EXPECT_LT(sent[0], 0.01);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kOtherRun), 5u);
  EXPECT_EQ(node.counters().runs, 1u);
  // The log names the run taken and the one refused, once however many of its commands came.
  const auto events = node.run_events();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, RunEvent::Kind::kBound);
  EXPECT_EQ(events[0].run_id, kRun);
  EXPECT_EQ(events[0].writer, kWriter);
  EXPECT_EQ(events[1].kind, RunEvent::Kind::kRefused);
  EXPECT_EQ(events[1].run_id, kOtherRun);
  EXPECT_EQ(events[1].serving_run_id, kRun);
  EXPECT_EQ(events[1].verdict, CommandVerdict::kOtherRun);
  EXPECT_STREQ(command_verdict_name(CommandVerdict::kOtherRun), "another run");
}

// Security off, anyone can write a command with the run's id (it is in every heartbeat). The
// node follows the writer that began the run: a forged command from another writer is
// refused, whatever its step, and so is a forged end of run.
TEST_F(NodeServingRun, FollowsTheWriterThatBeganTheRun) {
  send(node, of(kRun, kWriter, 0, 0.001));
  EXPECT_EQ(node.accept(of(kRun, kOtherWriter, 1, 0.02)), CommandVerdict::kUnknownWriter);
  EXPECT_EQ(node.accept(of(kRun, kOtherWriter, 9'000'000'000'000'000'000, 0.02)), CommandVerdict::kUnknownWriter);
  EXPECT_EQ(node.accept(end_of(kRun, kOtherWriter, 2)), CommandVerdict::kEndOfRun);
  EXPECT_EQ(node.serving_run(), kRun);  // the forged end changed nothing
  const FeedbackSample out = send(node, of(kRun, kWriter, 1, 0.002));
  EXPECT_EQ(out.step, 1);
  EXPECT_EQ(actuator.last(), 0.002);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kUnknownWriter), 2u);
  EXPECT_EQ(node.counters().dropped_total(), 2u);  // an end of run is not a drop
  EXPECT_EQ(node.run_events().size(), 2u);         // took the run; refused the writer (once)
}

// A command with a step no coordinator at this rate can have reached (9 x 10^18 took a node
// over: every real command after it was "not newer") is refused, and the run goes on. The
// bound: one step per tick since the last accepted command, plus max_step_lead (a second's
// worth, 1024 periods here, more than command_timeout_periods).
TEST_F(NodeServingRun, AnImpossibleStepIsRefusedAndTheRunGoesOn) {
  send(node, of(kRun, kWriter, 0, 0.001));
  send(node, of(kRun, kWriter, 1, 0.001));  // one tick since
  EXPECT_EQ(node.accept(of(kRun, kWriter, 9'000'000'000'000'000'000, 0.02)), CommandVerdict::kImpossibleStep);
  EXPECT_EQ(node.accept(of(kRun, kWriter, 1 + 1 + 1 + 1024 + 1, 0.001)), CommandVerdict::kImpossibleStep);
  EXPECT_EQ(node.accept(of(kRun, kWriter, 1 + 1 + 1 + 1024, 0.001)), CommandVerdict::kAccepted);
  idle(node);
  // Ticks without a command (lost commands) widen the bound one step each.
  for (int i = 0; i < 99; ++i) idle(node);
  EXPECT_EQ(node.accept(of(kRun, kWriter, 1027 + 100 + 1024 + 2, 0.001)), CommandVerdict::kImpossibleStep);
  EXPECT_EQ(node.accept(of(kRun, kWriter, 1027 + 100 + 1024 + 1, 0.001)), CommandVerdict::kAccepted);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kImpossibleStep), 3u);
  EXPECT_EQ(node.serving_run(), kRun);
  EXPECT_EQ(idle(node).step, 1027 + 100 + 1024 + 1);
}

// The run's end frees the node: it holds where the command was (as its watchdog would), its
// feedback names no run, and it serves the next run from that run's step 0. The ended run
// cannot come back, and an end of another run changes nothing.
TEST_F(NodeServingRun, TheRunsEndFreesTheNodeForTheNext) {
  for (std::int64_t step = 0; step < 20; ++step) send(node, of(kRun, kWriter, step, 1e-4 * static_cast<double>(step)));
  EXPECT_EQ(node.accept(end_of(kOtherRun, kOtherWriter, 21)), CommandVerdict::kEndOfRun);
  EXPECT_EQ(node.serving_run(), kRun);
  EXPECT_EQ(node.accept(end_of(kRun, kWriter, 20)), CommandVerdict::kEndOfRun);
  EXPECT_EQ(node.serving_run(), 0u);
  EXPECT_TRUE(node.holding());
  EXPECT_EQ(node.counters().holds, 1u);
  FeedbackSample out = idle(node);
  EXPECT_EQ(out.run_id, 0u);
  EXPECT_EQ(out.step, -1);
  EXPECT_EQ(out.status & transport::kNodeHolding, transport::kNodeHolding);
  EXPECT_EQ(actuator.last(), 19e-4);
  EXPECT_EQ(node.accept(end_of(kRun, kWriter, 20)), CommandVerdict::kEndOfRun);  // a repeat: nothing
  EXPECT_EQ(node.accept(of(kRun, kWriter, 20, 0.002)), CommandVerdict::kRunEnded);
  for (int i = 0; i < 2000; ++i) idle(node);  // waiting for a run is no loss: no new hold
  EXPECT_EQ(node.counters().holds, 1u);

  out = send(node, of(kOtherRun, kOtherWriter, 0, 0.0021));
  EXPECT_EQ(node.serving_run(), kOtherRun);
  EXPECT_EQ(out.run_id, kOtherRun);
  EXPECT_EQ(out.step, 0);
  EXPECT_FALSE(node.holding());
  EXPECT_EQ(node.accept(of(kRun, kWriter, 21, 0.002)), CommandVerdict::kOtherRun);
  EXPECT_EQ(node.counters().runs, 2u);
  EXPECT_EQ(node.counters().dropped(CommandVerdict::kEndOfRun), 3u);
  std::vector<RunEvent::Kind> kinds;
  for (const auto& e : node.run_events()) kinds.push_back(e.kind);
  EXPECT_EQ(kinds,
            (std::vector<RunEvent::Kind>{RunEvent::Kind::kBound, RunEvent::Kind::kEnded, RunEvent::Kind::kRefused,
                                         RunEvent::Kind::kBound, RunEvent::Kind::kRefused}));
}

// A coordinator that died sends no end: the loop frees the node after a silence
// (release_run); the node holds and serves the next run.
TEST_F(NodeServingRun, ReleasingASilentRunFreesTheNode) {
  send(node, of(kRun, kWriter, 0, 0.001));
  node.release_run();
  EXPECT_EQ(node.serving_run(), 0u);
  EXPECT_TRUE(node.holding());
  ASSERT_EQ(node.run_events().size(), 2u);
  EXPECT_EQ(node.run_events()[1].kind, RunEvent::Kind::kReleasedAfterSilence);
  EXPECT_EQ(node.run_events()[1].run_id, kRun);
  node.release_run();  // nothing to release
  EXPECT_EQ(node.run_events().size(), 2u);
  EXPECT_EQ(send(node, of(kOtherRun, kOtherWriter, 0, 0.001)).run_id, kOtherRun);
}

TEST_F(NodeServingRun, ACommandWithoutARunOrAtAnotherRateIsRefused) {
  EXPECT_EQ(node.accept(of(0, kWriter, 0, 0.001)), CommandVerdict::kNoRunId);
  CommandSample c = of(kRun, kWriter, 0, 0.001);
  c.control_period_s = 1.0 / 512.0;
  EXPECT_EQ(node.accept(c), CommandVerdict::kRateMismatch);
  EXPECT_EQ(node.serving_run(), 0u);  // refused before the node took the run
  c.control_period_s = kPeriod;
  EXPECT_EQ(node.accept(c), CommandVerdict::kAccepted);
  EXPECT_EQ(node.serving_run(), kRun);
}

}  // namespace run_identity

}  // namespace
}  // namespace rpsd::node
