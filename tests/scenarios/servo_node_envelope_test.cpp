// A servo node always has limits: the rig's envelope unless its file tightens it, never
// looser, and a hardware node must state its rig.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <string>

#include "../servo/paper_rig.h"
#include "example_files.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"

namespace rpsd::scenarios {
namespace {

std::string servo_node_error(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  try {
    load_servo_node(file, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ServoNodeEnvelope, ANodeWithoutLimitsGetsTheRigsEnvelope) {
  const auto node = load_servo_node(pier_node(), {parse_override("limits={}")});
  const servo::ServoSystemParameters rig = testing::paper_rig();
  // The MTS 244 rig of the parameter file: +/-127 mm, P_s A, the valve's full flow over A.
  const double force_n = rig.flow.supply_pressure_pa * rig.actuator.piston_area_m2;
  const double velocity_m_per_s = rig.flow.no_load_flow_gain_m3_per_s /
                                  std::sqrt(1.0 + rig.flow.flow_gain_rolloff * rig.flow.flow_gain_rolloff) /
                                  rig.actuator.piston_area_m2;
  const node::ChannelLimits& l = node.node.limits[0];
  EXPECT_EQ(l.max_stroke_m, 0.127);
  EXPECT_DOUBLE_EQ(l.max_force_n, force_n);
  EXPECT_DOUBLE_EQ(l.max_velocity_m_per_s, velocity_m_per_s);
  EXPECT_GT(l.force_guard_stiffness_n_per_m, 0.0);  // the simulated specimen's stiffness
}

TEST(ServoNodeEnvelope, ALimitBeyondTheEnvelopeIsRefusedWithItsKey) {
  const std::string e = servo_node_error(pier_node(), {parse_override("limits.max_stroke_m=[0.2]")});
  EXPECT_NE(e.find("limits.max_stroke_m"), std::string::npos) << e;
  EXPECT_NE(e.find("beyond the rig's stroke"), std::string::npos) << e;
  const std::string f = servo_node_error(pier_node(), {parse_override("limits.max_force_n=[1.0e6]")});
  EXPECT_NE(f.find("limits.max_force_n"), std::string::npos) << f;
}

// The increment limit stated per second is the same speed at the node's own rate, whatever
// node.control_rate_hz is set to; it may only tighten the rig's velocity capacity, and the
// per-period key beside it is refused (which would the node obey?).
TEST(ServoNodeEnvelope, AnIncrementPerSecondIsTheIncrementAtTheNodesOwnRate) {
  for (const int rate_hz : {1024, 2048, 4096}) {
    const auto node = load_servo_node(pier_node(), {parse_override("limits.max_increment_m_per_s=[0.5]"),
                                                    parse_override("node.control_rate_hz=" + std::to_string(rate_hz))});
    EXPECT_EQ(node.node.limits[0].max_increment_m_per_s, 0.5) << rate_hz;
    EXPECT_EQ(node.node.limits[0].max_increment_m, 0.5 / rate_hz) << rate_hz;
  }
  // The shipped file states it per second (1 m/s): 0.98 mm per period at its 1024 Hz.
  EXPECT_DOUBLE_EQ(load_servo_node(pier_node(), {}).node.limits[0].max_increment_m, 1.0 / 1024);
  // Today's per-period key works as before.
  const auto per_period = load_servo_node(
      pier_node(), {parse_override("limits={max_increment_m: [0.002]}"), parse_override("node.control_rate_hz=4096")});
  EXPECT_EQ(per_period.node.limits[0].max_increment_m, 0.002);
}

TEST(ServoNodeEnvelope, AnIncrementGivenPerPeriodAndPerSecondIsRefusedWithFileLineAndKey) {
  const std::string e = servo_node_error(pier_node(), {parse_override("limits.max_increment_m=[0.001]")});
  EXPECT_NE(e.find("bridge-pier-site-1.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("yaml:30:"), std::string::npos) << e;  // the line of max_increment_m_per_s
  EXPECT_NE(e.find("limits.max_increment_m_per_s"), std::string::npos) << e;
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
}

TEST(ServoNodeEnvelope, AnIncrementPerSecondBeyondTheRigsVelocityIsRefusedWithItsKey) {
  // The paper's MTS 244 moves at most 1.31 m/s; at 4096 Hz, 2 m/s would be 0.49 mm per period.
  const std::string e = servo_node_error(
      pier_node(), {parse_override("limits.max_increment_m_per_s=[2.0]"), parse_override("node.control_rate_hz=4096")});
  EXPECT_NE(e.find("limits.max_increment_m_per_s"), std::string::npos) << e;
  EXPECT_NE(e.find("beyond the rig's velocity capacity"), std::string::npos) << e;
}

TEST(ServoNodeEnvelope, AHardwareNodeThatStatesNoRigIsRefused) {
  const auto file = std::filesystem::temp_directory_path() / ("rpsd-udp-node-" + std::to_string(getpid()) + ".yaml");
  std::ofstream(file) << "node: {test_id: 7, site_id: 1, mode: lock_step, control_rate_hz: 1024}\n"
                         "dds: {domain_id: 0}\n"
                         "actuator: {kind: udp_controller, channels: 1, host: 127.0.0.1, port: 45999}\n";
  const std::string e = servo_node_error(file, {});
  std::filesystem::remove(file);
  EXPECT_NE(e.find("actuator.rig"), std::string::npos) << e;
  EXPECT_NE(e.find("must state its rig's envelope"), std::string::npos) << e;
}

}  // namespace
}  // namespace rpsd::scenarios
