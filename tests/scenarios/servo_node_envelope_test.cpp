// A servo node always has limits: the rig's envelope unless its file tightens it, never
// looser, and a hardware node must state its rig.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"

namespace rpsd::scenarios {
namespace {

std::filesystem::path pier_node() { return testing::source_dir() / "examples/nodes/bridge-pier-site-1.yaml"; }

std::string error_of(const std::filesystem::path& file, const std::vector<Override>& overrides) {
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
  const std::string e = error_of(pier_node(), {parse_override("limits.max_stroke_m=[0.2]")});
  EXPECT_NE(e.find("limits.max_stroke_m"), std::string::npos) << e;
  EXPECT_NE(e.find("beyond the rig's stroke"), std::string::npos) << e;
  const std::string f = error_of(pier_node(), {parse_override("limits.max_force_n=[1.0e6]")});
  EXPECT_NE(f.find("limits.max_force_n"), std::string::npos) << f;
}

TEST(ServoNodeEnvelope, AHardwareNodeThatStatesNoRigIsRefused) {
  const auto file = std::filesystem::temp_directory_path() / ("rpsd-udp-node-" + std::to_string(getpid()) + ".yaml");
  std::ofstream(file) << "node: {test_id: 7, site_id: 1, mode: lock_step, control_rate_hz: 1024}\n"
                         "dds: {domain_id: 0}\n"
                         "actuator: {kind: udp_controller, channels: 1, host: 127.0.0.1, port: 45999}\n";
  const std::string e = error_of(file, {});
  std::filesystem::remove(file);
  EXPECT_NE(e.find("actuator.rig"), std::string::npos) << e;
  EXPECT_NE(e.find("must state its rig's envelope"), std::string::npos) << e;
}

}  // namespace
}  // namespace rpsd::scenarios
