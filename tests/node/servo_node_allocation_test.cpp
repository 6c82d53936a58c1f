// The servo node allocates nothing per control period: the controller with its limits
// acting, events logged, bad commands dropped, the watchdog holding and ramping to safe,
// over the simulated plants, over the UDP adapter in both protocol versions (version 2
// tags and checks every datagram), over the Speedgoat adapter on TCP and UDP and over the NEES
// plugin adapter (the emulators' threads are not counted: only the control-loop thread must
// not allocate).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>

#include "../servo/paper_rig.h"
#include "allocation_counter.h"
#include "nees_plugin_test_site.h"
#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/servo_node_controller.h"
#include "rpsd/node/udp_controller_actuator.h"
#include "rpsd/servo/coupled_specimen_actuator.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/servo/transfer_function_plant.h"
#include "speedgoat_test_link.h"
#include "udp_test_link.h"

namespace rpsd::node {
namespace {

ServoNodeConfig node_config() {
  ServoNodeConfig c;
  c.test_id = 11;
  c.site_id = 2;
  c.channels = 2;
  c.control_period_s = 1.0 / 1024.0;
  for (int ch = 0; ch < 2; ++ch) {
    c.limits[ch].max_stroke_m = 0.015;  // the 20 mm sine below reaches it
    c.limits[ch].max_velocity_m_per_s = 0.1;
    c.limits[ch].max_increment_m = 0.01;
  }
  c.command_timeout_periods = 20;
  c.on_command_loss = LossAction::kRampToSafe;
  c.safe_ramp_velocity_m_per_s = 0.01;
  c.event_log_capacity = 16;  // fewer than the activations: the overflow path runs too
  return c;
}

struct RunResult {
  long allocations = 0;
  std::uint64_t activations = 0;
  std::uint64_t dropped = 0;
  bool reached_safe_state = false;
  std::uint64_t events_not_logged = 0;
  std::uint64_t missed_periods = 0;
};

// 3000 periods of commands (a 2 Hz, 20 mm sine with a bad command every 7th period and a
// 10-period gap), then silence until the node has ramped to its safe state.
RunResult run(ServoNodeController& node, int silent_periods) {
  const double x0[] = {0.0, 0.0};
  node.start(x0);
  transport::CommandSample command;
  command.test_id = 11;
  command.run_id = 0x5eed;
  command.site_id = 2;
  command.channels = 2;
  transport::FeedbackSample feedback;
  const double dt = node.config().control_period_s;
  rpsd::testing::begin_counting_allocations();
  for (int i = 1; i <= 3000; ++i) {
    const bool gap = i > 1000 && i <= 1010;  // shorter than the command timeout
    if (!gap) {
      command.step = i;
      command.time_s = i * dt;
      command.displacement_m[0] = 0.02 * std::sin(2.0 * std::numbers::pi * 2.0 * command.time_s);
      command.displacement_m[1] = -0.5 * command.displacement_m[0];
      node.accept(command);
      if (i % 7 == 0) node.accept(command);  // a duplicate, dropped
    }
    node.tick(feedback);
  }
  for (int i = 0; i < silent_periods; ++i) node.tick(feedback);
  RunResult result;
  result.allocations = rpsd::testing::end_counting_allocations().total();
  for (auto n : node.counters().limit_activations) result.activations += n;
  result.dropped = node.counters().dropped_total();
  result.reached_safe_state = node.in_safe_state() && node.command_m()[0] == 0.0;
  result.events_not_logged = node.events_not_logged();
  result.missed_periods = node.counters().missed_periods;
  return result;
}

TEST(ServoNodeAllocation, CounterSeesAllocations) {
  rpsd::testing::begin_counting_allocations();
  auto* p = new int(1);
  rpsd::testing::keep(p);
  delete p;
  EXPECT_EQ(rpsd::testing::end_counting_allocations().operator_new, 1);
}

TEST(ServoNodeAllocation, NoAllocationPerTickOverSimulatedPlants) {
  servo::ServoHydraulicPlant paper(rpsd::testing::paper_rig());
  servo::TransferFunctionPlant benchmark(
      {{servo::Polynomial{2.18385e13},
        servo::Polynomial{2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13}},
       1.19e6,
       8192.0,
       {}});
  servo::Plant* plants[] = {&paper, &benchmark};
  servo::SimulatedActuator actuator(plants);
  ServoNodeController node(node_config(), actuator);
  const RunResult r = run(node, 2000);
  EXPECT_EQ(r.allocations, 0);
  EXPECT_GT(r.activations, 16u);  // limits acted and the log overflowed: those paths ran
  EXPECT_GT(r.events_not_logged, 0u);
  EXPECT_EQ(r.dropped, 3000u / 7 - 2u);    // the duplicates, less the two that fell in the gap (1001, 1008)
  EXPECT_GE(r.missed_periods, 10u + 20u);  // the gap, then the silence up to the timeout
  EXPECT_TRUE(r.reached_safe_state);
}

// Two actuators under one coupled specimen (a column top's translation and rotation, large-
// displacement geometry: Newton every tick), the node's limits and watchdog acting as above.
TEST(ServoNodeAllocation, NoAllocationPerTickOverACoupledSpecimen) {
  const servo::PlantConfig plant = servo::coupled_plant_config(rpsd::testing::paper_rig());
  auto bottom = servo::make_plant(plant), top = servo::make_plant(plant);
  servo::Plant* plants[] = {bottom.get(), top.get()};
  setups::PlanarGeometry g;
  g.geometry = setups::Geometry::kLargeDisplacement;
  g.dof_count = 2;
  g.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation, setups::DofMotion::kTranslationY};
  g.actuators[0] = {"bottom", {-2.0, 0.0}, {0.0, 0.0}};
  g.actuators[1] = {"top", {-2.0, 0.8}, {0.0, 0.8}};
  Eigen::MatrixXd k(2, 2), c(2, 2);
  k << 1.5e6, -1.5e6, -1.5e6, 2.0e6;
  c << 2e4, 0.0, 0.0, 1e4;
  servo::CoupledSpecimenActuator actuator(plants, setups::PlanarSetup(g), k, c);
  ServoNodeController node(node_config(), actuator);
  const RunResult r = run(node, 2000);
  EXPECT_EQ(r.allocations, 0);
  EXPECT_GT(r.activations, 16u);
  EXPECT_NE(actuator.actuator_loads_n()[1], 0.0);  // the specimen loaded the top actuator
  EXPECT_EQ(node.counters().actuator_faults, 0u);
  EXPECT_TRUE(r.reached_safe_state);
}

void expect_no_allocation_per_tick_over_the_udp_adapter(int version) {
  servo::TransferFunctionPlant a({{servo::Polynomial{1.0}, servo::Polynomial{1.0, 0.01}}, 1e5, 8192.0, {}});
  servo::TransferFunctionPlant b({{servo::Polynomial{1.0}, servo::Polynomial{1.0, 0.02}}, 1e5, 8192.0, {}});
  servo::Plant* plants[] = {&a, &b};
  ControllerEmulator emulator(plants, testing::emulator_config(version));
  const double x0[] = {0.0, 0.0};
  emulator.start(x0);
  UdpControllerActuator adapter(testing::adapter_config(emulator, 2));
  testing::pair(emulator, adapter);
  ServoNodeController node(node_config(), adapter);
  RunResult r;
  {
    const testing::Serving serving(emulator);
    r = run(node, 2000);
  }
  EXPECT_EQ(r.allocations, 0);
  EXPECT_EQ(adapter.counters().missed_replies, 0u);
  EXPECT_EQ(adapter.counters().replies, 3000u + 2000u);  // one a tick
  EXPECT_EQ(node.counters().actuator_no_replies, 0u);
  EXPECT_EQ(emulator.counters().sessions, 1u);
  EXPECT_TRUE(r.reached_safe_state);
}

TEST(ServoNodeAllocation, NoAllocationPerTickOverTheUdpAdapter) {
  expect_no_allocation_per_tick_over_the_udp_adapter(udp_protocol::kVersion1);
}

TEST(ServoNodeAllocation, NoAllocationPerTickOverTheAuthenticatedUdpAdapter) {
  expect_no_allocation_per_tick_over_the_udp_adapter(udp_protocol::kVersion2);
}

// The plugin adapter writes, sends and parses each step's three lines in fixed buffers (the
// site emulator's thread is not counted).
TEST(ServoNodeAllocation, NoAllocationPerTickOverTheNeesPluginAdapter) {
  PluginSiteConfig config;
  config.control_points = {
      {"LBCB1", {{"x", "translation", -100, 100, 1000, 1}, {"y", "translation", -100, 100, 1000, 1}}}};
  testing::EmulatedSite site(config, {1e5, 2e5});
  NeesPluginActuator adapter(testing::plugin_adapter_config(
      site.emulator(), {{"LBCB1", nees_plugin::Axis::kX, nees_plugin::Motion::kTranslation, 1000, 1},
                        {"LBCB1", nees_plugin::Axis::kY, nees_plugin::Motion::kTranslation, 1000, 1}}));
  ServoNodeController node(node_config(), adapter);
  RunResult r;
  {
    const testing::ServingSite serving(site.emulator());
    r = run(node, 2000);
  }
  EXPECT_EQ(r.allocations, 0);
  EXPECT_EQ(adapter.counters().readings, 1u + 3000u + 2000u);  // the start's step, then one a tick
  EXPECT_EQ(adapter.failed_side(), "none");
  EXPECT_EQ(node.counters().actuator_faults, 0u);
  EXPECT_TRUE(r.reached_safe_state);
}

void expect_no_allocation_per_tick_over_the_speedgoat_adapter(bool udp) {
  testing::IdealTarget target(testing::target_config(udp, 2));
  SpeedgoatActuator adapter(testing::node_config(target.emulator->port(), udp, 2));
  ServoNodeController node(node_config(), adapter);
  RunResult r;
  {
    const testing::ServingTarget serving(*target.emulator);
    r = run(node, 2000);
  }
  EXPECT_EQ(r.allocations, 0);
  EXPECT_EQ(adapter.counters().missed_deadlines, 0u);
  EXPECT_EQ(adapter.counters().handshakes, 3000u + 2000u);  // one a tick
  EXPECT_EQ(node.counters().actuator_no_replies, 0u);
  EXPECT_TRUE(r.reached_safe_state);
}

TEST(ServoNodeAllocation, NoAllocationPerTickOverTheSpeedgoatAdapterOnTcp) {
  expect_no_allocation_per_tick_over_the_speedgoat_adapter(false);
}

TEST(ServoNodeAllocation, NoAllocationPerTickOverTheSpeedgoatAdapterOnUdp) {
  expect_no_allocation_per_tick_over_the_speedgoat_adapter(true);
}

}  // namespace
}  // namespace rpsd::node
