// Mixed control at the node (issue 30): a channel declared in force control holds the force its
// commands ask for, within its own limits; a command of another mode faults the node; and a
// force channel whose piston runs away (a softening or broken specimen) stops in the safe state:
// displacement control at its measured position, the fault latched with its text.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "node_period.h"
#include "rpsd/node/servo_node_controller.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {
namespace {

using servo::ControlMode;

servo::ServoSystemParameters force_rig() {
  const char* env = std::getenv("RPSD_SOURCE_DIR");
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? env : RPSD_TEST_SOURCE_DIR;
  servo::ServoSystemParameters p = scenarios::load_servo_parameters(dir / "examples/servo/paper-mts-244.yaml");
  p.controller.force_gain_v_per_n = 1e-5;  // stable on the paper's 7080 kg specimen (tests/servo)
  return p;
}

// Channel 0 follows displacements, channel 1 holds a force; both on the paper's rig.
struct MixedNode {
  explicit MixedNode(double max_stroke_m = 0.1, double max_velocity_m_per_s = 0.5)
      : a(force_rig()), b(force_rig()), actuator(plants) {
    config.test_id = 7;
    config.site_id = 1;
    config.channels = 2;
    config.control_period_s = kNodePeriodS;
    config.control[1] = ControlMode::kForce;
    for (auto& l : config.limits) {
      l.max_stroke_m = max_stroke_m;
      l.max_velocity_m_per_s = max_velocity_m_per_s;
      l.max_force_n = 60e3;
      l.max_force_command_n = 20e3;
      l.max_force_rate_n_per_s = 50e3;
    }
    controller = std::make_unique<ServoNodeController>(config, actuator);
    const double start[2] = {0.0, 0.0};
    controller->start(start);
  }

  CommandVerdict send(double x0_m, double f1_n, std::uint8_t mode1 = transport::kForceControl) {
    transport::CommandSample command;
    command.test_id = 7;
    command.site_id = 1;
    command.run_id = 0x7e57;
    command.writer = 1;
    command.channels = 2;
    command.step = ++step;
    command.time_s = static_cast<double>(step) * kNodePeriodS;
    command.displacement_m[0] = x0_m;
    command.control_mode[1] = mode1;
    command.force_n[1] = f1_n;
    return controller->accept(command);
  }
  void tick() { controller->tick(feedback); }

  servo::ServoHydraulicPlant a, b;
  std::array<servo::Plant*, 2> plants{&a, &b};
  servo::SimulatedActuator actuator;
  ServoNodeConfig config;
  std::unique_ptr<ServoNodeController> controller;
  transport::FeedbackSample feedback;
  std::int64_t step = -1;
};

TEST(MixedControl, AForceChannelHoldsItsForceWhileTheOtherFollowsItsDisplacement) {
  MixedNode node;
  for (int i = 0; i < 20 * 1024; ++i) {
    ASSERT_EQ(node.send(0.004, 10e3), CommandVerdict::kAccepted);
    node.tick();
  }
  ASSERT_FALSE(node.controller->faulted());
  EXPECT_EQ(node.controller->control_mode()[1], ControlMode::kForce);
  EXPECT_NEAR(node.feedback.displacement_m[0], 0.004, 1e-4);
  // The loop's steady state with the paper's leakage: F = F_u g A / (g A + C_l) (tests/servo).
  const auto& p = node.b.parameters();
  const double gA = p.flow.no_load_flow_gain_m3_per_s * p.servovalve.static_gain_per_v() *
                    p.controller.force_gain_v_per_n * p.actuator.piston_area_m2;
  const double settled_n = 10e3 * gA / (gA + p.actuator.leakage_m3_per_s_per_pa);
  EXPECT_NEAR(node.feedback.force_n[1], settled_n, 0.01 * settled_n);
  EXPECT_NEAR(node.feedback.displacement_m[1], node.feedback.force_n[1] / p.specimen.stiffness.initial_n_per_m, 2e-5);
}

TEST(MixedControl, TheForceCommandIsHeldToItsLimitAndRate) {
  MixedNode node;
  double previous = node.controller->force_command_n()[1];
  for (int i = 0; i < 1024; ++i) {
    node.send(0.0, 50e3);  // beyond max_force_command_n
    node.tick();
    const double f = node.controller->force_command_n()[1];
    ASSERT_LE(std::abs(f - previous), 50e3 * kNodePeriodS * (1.0 + 1e-12)) << "tick " << i;
    ASSERT_LE(std::abs(f), 20e3);
    previous = f;
  }
  EXPECT_EQ(previous, 20e3);
  EXPECT_NE(node.feedback.limit_flags & transport::kLimitForce, 0u);
}

TEST(MixedControl, ACommandInAnotherModeThanTheDeclaredOneFaultsTheNode) {
  MixedNode node;
  node.send(0.0, 1e3);
  node.tick();
  EXPECT_EQ(node.send(0.0, 0.0, transport::kDisplacementControl), CommandVerdict::kModeMismatch);
  EXPECT_TRUE(node.controller->faulted());
  EXPECT_NE(std::string(node.controller->fault_text().data()).find("channel 1 in control mode 0, declared force"),
            std::string::npos)
      << node.controller->fault_text().data();
  node.tick();
  EXPECT_NE(node.feedback.status & transport::kNodeFault, 0u);
  EXPECT_EQ(node.controller->control_mode()[1], ControlMode::kDisplacement);

  MixedNode other;
  transport::CommandSample command;
  command.test_id = 7;
  command.site_id = 1;
  command.run_id = 1;
  command.channels = 2;
  command.step = 0;
  command.control_mode = {transport::kForceControl, transport::kForceControl};
  EXPECT_EQ(other.controller->accept(command), CommandVerdict::kModeMismatch);
  EXPECT_NE(
      std::string(other.controller->fault_text().data()).find("channel 0 in control mode 1, declared displacement"),
      std::string::npos)
      << other.controller->fault_text().data();
}

TEST(MixedControl, AForceChannelWhoseMeasuredStrokePassesItsLimitHoldsItsMeasuredPositionFaulted) {
  // 15 kN on the paper's springs would take the piston to ~20 mm: its stroke limit is 10 mm.
  MixedNode node(0.010);
  double x_at_fault = 0.0;
  int ticks = 0;
  for (; ticks < 20 * 1024 && !node.controller->faulted(); ++ticks) {
    node.send(0.0, 15e3);
    node.tick();
    x_at_fault = node.feedback.displacement_m[1];
  }
  ASSERT_TRUE(node.controller->faulted()) << "never stopped; x = " << node.feedback.displacement_m[1];
  EXPECT_GT(x_at_fault, 0.010);
  EXPECT_LT(x_at_fault, 0.0105);
  EXPECT_NE(std::string(node.controller->fault_text().data()).find("stroke limit on channel 1"), std::string::npos)
      << node.controller->fault_text().data();
  EXPECT_NE(node.feedback.status & transport::kNodeFault, 0u);
  EXPECT_NE(node.feedback.limit_flags & transport::kLimitStroke, 0u);
  // The safe state: displacement control, holding where the piston was measured.
  for (int i = 0; i < 2 * 1024; ++i) {
    node.send(0.0, 15e3);
    node.tick();
    EXPECT_EQ(node.controller->control_mode()[1], ControlMode::kDisplacement);
  }
  EXPECT_NEAR(node.feedback.displacement_m[1], x_at_fault, 5e-4);
  EXPECT_NEAR(node.controller->command_m()[1], x_at_fault, 1e-4);
}

TEST(MixedControl, AForceChannelWhoseMeasuredVelocityPassesItsLimitHoldsItsMeasuredPositionFaulted) {
  // 10 kN at 50 kN/s on the paper's springs moves the piston at up to ~40 mm/s: the limit is 10.
  MixedNode node(0.1, 0.010);
  int ticks = 0;
  for (; ticks < 4 * 1024 && !node.controller->faulted(); ++ticks) {
    node.send(0.0, 10e3);
    node.tick();
  }
  ASSERT_TRUE(node.controller->faulted());
  EXPECT_NE(std::string(node.controller->fault_text().data()).find("velocity limit on channel 1"), std::string::npos)
      << node.controller->fault_text().data();
  EXPECT_EQ(node.controller->control_mode()[1], ControlMode::kDisplacement);
  const double x_held = node.controller->command_m()[1];
  for (int i = 0; i < 1024; ++i) node.tick();
  EXPECT_NEAR(node.feedback.displacement_m[1], x_held, 1e-3);
}

TEST(MixedControl, AForceChannelOnAPlantWithoutAForceLoopIsRefused) {
  servo::PureDelayPlant a({0.0, 1e5, 8192.0, {}});
  std::array<servo::Plant*, 1> plants{&a};
  servo::SimulatedActuator actuator(plants);
  ServoNodeConfig config;
  config.control[0] = ControlMode::kForce;
  config.limits[0] = {0.1, 0.5, 10e3};
  config.limits[0].max_force_rate_n_per_s = 1e4;
  EXPECT_THROW(
      {
        try {
          ServoNodeController controller(config, actuator);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("control[0]"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
}

TEST(MixedControl, AForceChannelNeedsAForceRateLimit) {
  ServoNodeConfig config;
  config.control[0] = ControlMode::kForce;
  config.limits[0] = {0.1, 0.5, 10e3};
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config.limits[0].max_force_rate_n_per_s = 1e4;
  EXPECT_NO_THROW(config.validate());
}

}  // namespace
}  // namespace rpsd::node
