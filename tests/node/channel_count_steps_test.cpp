// A node of one channel steps through the controller's code compiled for one channel; any other
// count through the same code over its run-time count. Both must decide and command alike: a
// channel of a node of one and the same channel beside an identical one in a node of two get the
// same commands, limits, refusals and feedback, to the last bit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "../servo/paper_rig.h"
#include "node_period.h"
#include "rpsd/node/lock_step_node.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {
namespace {

constexpr std::uint64_t kChannelCountRun = 0x51;

ServoNodeConfig clamping_config(int channels) {
  ServoNodeConfig c;
  c.test_id = 4;
  c.site_id = 2;
  c.channels = channels;
  c.control_period_s = kNodePeriodS;
  for (int ch = 0; ch < channels; ++ch) {
    // Tight enough that the stroke, velocity and acceleration limits clamp the sine below.
    c.limits[ch].max_stroke_m = 0.004;
    c.limits[ch].max_velocity_m_per_s = 0.05;
    c.limits[ch].max_acceleration_m_per_s2 = 40.0;
    c.limits[ch].stop_deceleration_m_per_s2 = 20.0;
  }
  return c;
}

transport::CommandSample command_on_every_channel(int channels, std::int64_t step, double x) {
  transport::CommandSample c;
  c.test_id = 4;
  c.site_id = 2;
  c.run_id = kChannelCountRun;
  c.channels = static_cast<std::uint8_t>(channels);
  c.step = step;
  c.time_s = static_cast<double>(step) * kNodePeriodS;
  for (int ch = 0; ch < channels; ++ch) c.displacement_m[ch] = x;
  return c;
}

// A node of `channels` identical channels on the paper's servo-hydraulic plants.
struct Node {
  explicit Node(int channels)
      : pointers{&first, &second},
        actuator(std::span<servo::Plant* const>(pointers, static_cast<std::size_t>(channels))),
        controller(clamping_config(channels), actuator) {
    const double x0[] = {0.001, 0.001};
    controller.start(std::span<const double>(x0, static_cast<std::size_t>(channels)));
  }
  servo::ServoHydraulicPlant first{rpsd::testing::paper_rig()}, second{rpsd::testing::paper_rig()};
  servo::Plant* pointers[2];
  servo::SimulatedActuator actuator;
  ServoNodeController controller;
};

TEST(ServoNodeChannelCount, OneChannelStepsAsTheSameChannelOfANodeOfTwo) {
  Node one(1), two(2);
  int limited = 0, refused = 0;
  for (std::int64_t step = 0; step < 600; ++step) {
    // A sine beyond the stroke and too fast for the velocity limit; now and then a command the
    // node must refuse (not finite, a repeated step), which neither node may answer.
    double x = 0.006 * std::sin(2.0 * std::numbers::pi * 3.0 * static_cast<double>(step) * kNodePeriodS);
    std::int64_t sent_step = step;
    if (step % 97 == 50) x = std::numeric_limits<double>::quiet_NaN();
    if (step % 89 == 40) sent_step = step - 1;
    transport::FeedbackSample a, b;
    const bool answered_one = answer_lock_step(one.controller, command_on_every_channel(1, sent_step, x), a);
    const bool answered_two = answer_lock_step(two.controller, command_on_every_channel(2, sent_step, x), b);
    ASSERT_EQ(answered_one, answered_two) << "step " << step;
    if (!answered_one) {
      ++refused;
      continue;
    }
    ASSERT_EQ(a.step, b.step) << "step " << step;
    ASSERT_EQ(a.displacement_m[0], b.displacement_m[0]) << "step " << step;
    ASSERT_EQ(a.force_n[0], b.force_n[0]) << "step " << step;
    ASSERT_EQ(b.displacement_m[0], b.displacement_m[1]) << "step " << step;
    ASSERT_EQ(a.displacement_m[1], 0.0) << "step " << step;  // beyond the channel: 0
    ASSERT_EQ(a.status, b.status) << "step " << step;
    ASSERT_EQ(a.limit_flags, b.limit_flags) << "step " << step;
    ASSERT_EQ(one.controller.command_m()[0], two.controller.command_m()[0]) << "step " << step;
    ASSERT_EQ(one.controller.latest_measurement().displacement_m[0],
              two.controller.latest_measurement().displacement_m[0])
        << "step " << step;
    ASSERT_EQ(one.controller.latest_measurement().force_n[0], two.controller.latest_measurement().force_n[0])
        << "step " << step;
    limited += a.limit_flags != transport::kLimitNone ? 1 : 0;
  }
  // The run exercised the limits and the refusals, not only a quiet follow.
  EXPECT_GT(limited, 50);
  EXPECT_GT(refused, 5);
  EXPECT_EQ(one.controller.counters().dropped_total(), two.controller.counters().dropped_total());
  EXPECT_EQ(one.controller.counters().by_verdict, two.controller.counters().by_verdict);
  EXPECT_EQ(one.controller.counters().ticks, two.controller.counters().ticks);
  for (int k = 0; k < kLimitKinds; ++k) {
    // Two identical channels: every activation twice, every tick it acts once.
    EXPECT_EQ(2 * one.controller.counters().limit_activations[k], two.controller.counters().limit_activations[k]);
    EXPECT_EQ(one.controller.counters().limit_active_ticks[k], two.controller.counters().limit_active_ticks[k]);
  }
}

}  // namespace
}  // namespace rpsd::node
