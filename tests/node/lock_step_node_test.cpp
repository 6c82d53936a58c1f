// The in-process node is the node: driven through the in-process link, its feedback is the
// actuator's reading for every command it accepts, and a command the controller refuses gets
// no answer (the link reports a timeout, never an old measurement as new).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../servo/paper_rig.h"
#include "rpsd/node/lock_step_node.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/transport/in_process_link.h"

namespace rpsd::node {
namespace {

constexpr double kPeriodS = 1.0 / 2048.0;

double sine_command(int i) { return 0.002 + 0.004 * std::sin(2.0 * std::numbers::pi * i * kPeriodS); }

TEST(LockStepNode, FeedbackIsTheActuatorReadingOfEachAcceptedCommand) {
  const auto rig = rpsd::testing::paper_rig();
  servo::ServoHydraulicPlant for_node(rig), for_actuator(rig);
  servo::Plant* node_plants[] = {&for_node};
  servo::Plant* actuator_plants[] = {&for_actuator};
  servo::SimulatedActuator node_actuator(node_plants), reference(actuator_plants);
  ServoNodeConfig config;
  config.test_id = 3;
  config.site_id = 2;
  config.control_period_s = kPeriodS;
  ServoNodeController controller(config, node_actuator);
  const double x0[] = {0.001};
  controller.start(x0);
  reference.start(x0);
  LockStepNode node(controller);
  transport::InProcessLink link(node);

  transport::CommandSample command;
  command.test_id = 3;
  command.run_id = 0x3;
  command.site_id = 2;
  command.channels = 1;
  transport::FeedbackSample feedback;
  servo::ActuatorReading reading;
  for (int i = 0; i < 512; ++i) {
    command.step = i;
    command.displacement_m[0] = sine_command(i);
    ASSERT_EQ(link.send(command), transport::LinkStatus::kOk);
    ASSERT_EQ(link.receive(feedback), transport::LinkStatus::kOk);
    const double u[] = {command.displacement_m[0]};
    reference.exchange(u, kPeriodS, reading);
    ASSERT_EQ(feedback.step, i);
    ASSERT_EQ(feedback.status, transport::kNodeOk);
    ASSERT_EQ(feedback.displacement_m[0], reading.displacement_m[0]);
    ASSERT_EQ(feedback.force_n[0], reading.force_n[0]);
  }

  // A repeated step and another test's command are refused: no answer, no tick.
  const auto ticks = controller.counters().ticks;
  ASSERT_EQ(link.send(command), transport::LinkStatus::kOk);
  EXPECT_EQ(link.receive(feedback), transport::LinkStatus::kTimeout);
  command.step = 512;
  command.test_id = 4;
  ASSERT_EQ(link.send(command), transport::LinkStatus::kOk);
  EXPECT_EQ(link.receive(feedback), transport::LinkStatus::kTimeout);
  EXPECT_EQ(controller.counters().ticks, ticks);
  EXPECT_EQ(controller.counters().dropped(CommandVerdict::kNotNewer), 1u);
  EXPECT_EQ(controller.counters().dropped(CommandVerdict::kWrongTestId), 1u);
}

}  // namespace
}  // namespace rpsd::node
