// rpsd servo-node files: the real-time requests a node makes of its host.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../servo/paper_rig.h"
#include "example_files.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/servo/signal_converter.h"

namespace rpsd::scenarios {
namespace {

TEST(ServoNodeFile, ARealTimeNodeKeepsTheCpusAwakeUnlessTurnedOff) {
  const node::ServoNodeSetup file = load_servo_node(pier_node());
  EXPECT_EQ(file.mode, node::ServoNodeSetup::Mode::kRealTime);
  EXPECT_TRUE(file.realtime.keep_cpus_awake);
  EXPECT_EQ(file.realtime.fifo_priority, 80);
  EXPECT_EQ(file.realtime.loop_cpu, -1);  // not pinned unless asked
  EXPECT_EQ(load_servo_node(pier_node(), {parse_override("node.loop_cpu=1")}).realtime.loop_cpu, 1);
  try {
    load_servo_node(pier_node(), {parse_override("node.loop_cpu=1024")});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("node.loop_cpu"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(load_servo_node(pier_node(), {parse_override("node.keep_cpus_awake=false")}).realtime.keep_cpus_awake);
  try {
    load_servo_node(pier_node(), {parse_override("node.keep_cpus_awake=7")});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("node.keep_cpus_awake"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::scenarios

namespace rpsd::scenarios {
namespace {

TEST(ServoNodeFile, ANodeRunsTheBenchmarksControllerAndConvertersAndTheRigIsItsDefaultLimit) {
  const node::ServoNodeSetup file = load_servo_node(testing::source_dir() / "examples/nodes/rths-benchmark-site.yaml");
  const auto& simulated = std::get<node::SimulatedActuatorParameters>(file.actuator);
  const auto& plant = std::get<servo::FeedbackControlledPlantParameters>(simulated.plant);
  ASSERT_TRUE(plant.controller);
  EXPECT_EQ(plant.controller->proportional, 2.0);
  // The released chain, as the case scenarios have it: unit gains, 2^-18 steps on the reference,
  // the error and the command, no rail on the force.
  EXPECT_EQ(plant.converters.force.units_per_volt, 1.0);
  EXPECT_EQ(plant.converters.command.saturation_v, 3.8);
  EXPECT_EQ(servo::SignalConverter(plant.converters.reference).step_units(), std::ldexp(1.0, -18));
  EXPECT_EQ(servo::SignalConverter(plant.converters.error).step_units(), std::ldexp(1.0, -18));
  EXPECT_FALSE(servo::reading_ranges_of(simulated.plant).force_n.bounded());
  EXPECT_EQ(plant.plant.specimen_mass_kg, 29.13);
  // No limits given: the rig's envelope (the benchmark's +/-7 mm, 8.9 kN).
  EXPECT_EQ(file.node.limits[0].max_stroke_m, 0.007);
  EXPECT_EQ(file.node.limits[0].max_force_n, 8900.0);
}

}  // namespace
}  // namespace rpsd::scenarios
