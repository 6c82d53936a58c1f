// The Speedgoat example files (a node of kind openfresco_speedgoat and the emulated target
// that stands in for it) read as they say, and a Speedgoat section the node cannot serve is
// refused at its file, line and key.
#include <gtest/gtest.h>

#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"

namespace rpsd::scenarios {
namespace {

std::filesystem::path node_file() { return testing::source_dir() / "examples/nodes/speedgoat-node.yaml"; }
std::filesystem::path target_file() { return testing::source_dir() / "examples/nodes/speedgoat-target-emulator.yaml"; }

TEST(SpeedgoatFiles, TheExampleNodeReadsAsItSays) {
  const node::ServoNodeSetup setup = load_servo_node(node_file());
  const auto& p = std::get<node::SpeedgoatParameters>(setup.actuator);
  EXPECT_EQ(p.transport, node::SpeedgoatTransport::kTcp);
  EXPECT_EQ(p.port, 45990);
  EXPECT_EQ(p.signals.vector_doubles, 256);
  ASSERT_EQ(p.signals.control.size(), 1u);
  EXPECT_EQ(p.signals.control[0].reference, node::speedgoat::Reference::kRelative);
  ASSERT_EQ(p.signals.daq.size(), 3u);
  EXPECT_EQ(p.signals.daq[1].quantity, node::speedgoat::DaqQuantity::kForce);
  EXPECT_EQ(p.signals.daq[1].signal_per_si, 1e-3);
  EXPECT_EQ(p.signals.daq[2].quantity, node::speedgoat::DaqQuantity::kUnused);
  EXPECT_EQ(p.max_missed_replies, 3);
  EXPECT_EQ(setup.node.limits[0].max_force_n, 156.0e3);  // the rig's, no tighter limit given
  EXPECT_EQ(std::get<node::SpeedgoatParameters>(
                load_servo_node(node_file(), {parse_override("actuator.transport=udp")}).actuator)
                .transport,
            node::SpeedgoatTransport::kUdp);
}

TEST(SpeedgoatFiles, TheExampleTargetReadsAsItSays) {
  const node::SpeedgoatEmulatorSetup setup = load_speedgoat_emulator(target_file());
  EXPECT_FALSE(setup.target.udp);
  EXPECT_EQ(setup.target.port, 45990);
  EXPECT_EQ(setup.target.daq_offsets, (std::vector<double>{2.5, 0.4, 0.0}));
  ASSERT_EQ(setup.target.daq.size(), 3u);
  EXPECT_EQ(setup.target.daq[1].quantity, "force");
  EXPECT_EQ(setup.channels, 1);
}

// The message of the ConfigError `overrides` give the example node, or "" when it reads.
std::string speedgoat_node_error(const std::vector<std::string>& overrides) {
  std::vector<Override> parsed;
  for (const auto& o : overrides) parsed.push_back(parse_override(o));
  try {
    load_servo_node(node_file(), parsed);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SpeedgoatFiles, AForceControlSignalOfADisplacementChannelIsRefused) {
  try {
    load_servo_node(testing::source_dir() / "tests/scenarios/data/speedgoat/force-control-node.yaml");
    FAIL() << "a force control signal of a displacement channel was taken";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("force-control-node.yaml:6:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("actuator.kind: channel 0 cannot be in displacement control: "
                                         "control_signals has a force signal for channel 0"),
              std::string::npos)
        << e.what();
  }
}

// The node file of the channel-in-force-control example; or the message of the ConfigError its
// overrides give.
std::filesystem::path force_channel_file() {
  return testing::source_dir() / "tests/scenarios/data/speedgoat/force-channel-node.yaml";
}
std::string force_channel_error(const std::string& override_text) {
  try {
    load_servo_node(force_channel_file(), {parse_override(override_text)});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SpeedgoatFiles, AChannelInForceControlTakesAForceSignalAndItsOwnLimits) {
  const node::ServoNodeSetup setup = load_servo_node(force_channel_file());
  EXPECT_EQ(setup.node.control[0], servo::ControlMode::kDisplacement);
  EXPECT_EQ(setup.node.control[1], servo::ControlMode::kForce);
  EXPECT_EQ(setup.node.limits[1].max_force_command_n, 600e3);
  EXPECT_EQ(setup.node.limits[1].max_force_rate_n_per_s, 50e3);
  const auto& p = std::get<node::SpeedgoatParameters>(setup.actuator);
  EXPECT_EQ(p.signals.control[2].quantity, node::speedgoat::ControlQuantity::kForce);
  EXPECT_EQ(p.signals.control[3].quantity, node::speedgoat::ControlQuantity::kControlMode);
}

TEST(SpeedgoatFiles, AChannelInForceControlWithoutAForceSignalOrARateLimitIsRefused) {
  const std::string no_signal = force_channel_error("actuator.control=[force, force]");
  EXPECT_NE(no_signal.find("actuator.control: channel 0 cannot be in force control: control_signals has no force "
                           "signal for channel 0"),
            std::string::npos)
      << no_signal;
  const std::string no_rate = force_channel_error("limits={max_force_n: [500.0e3, 800.0e3]}");
  EXPECT_NE(no_rate.find("limits.max_force_rate_n_per_s: channel 1 is in force control"), std::string::npos) << no_rate;
  const std::string beyond = force_channel_error("limits.max_force_command_n=[500.0e3, 900.0e3]");
  EXPECT_NE(beyond.find("max_force_command_n"), std::string::npos) << beyond;
}

TEST(SpeedgoatFiles, EachChannelNeedsADisplacementAndAForceDaqSignal) {
  const std::string e =
      speedgoat_node_error({"actuator.daq_signals=[{channel: 0, quantity: displacement, signal_per_si: 1}]"});
  EXPECT_NE(e.find("actuator.daq_signals: channel 0 has no force signal"), std::string::npos) << e;
}

TEST(SpeedgoatFiles, OnlyADisplacementControlSignalMayBeRelative) {
  const std::string e =
      speedgoat_node_error({"actuator.control_signals=[{channel: 0, quantity: displacement, signal_per_si: 1}, "
                            "{channel: 0, quantity: velocity, signal_per_si: 1, reference: relative}]"});
  EXPECT_NE(e.find("actuator.control_signals[1].reference: only a displacement control signal can be relative"),
            std::string::npos)
      << e;
}

TEST(SpeedgoatFiles, AHardwareNodeMustStateItsRig) {
  EXPECT_NE(speedgoat_node_error({"actuator.rig=null"}).find("actuator.rig"), std::string::npos);
  EXPECT_NE(
      speedgoat_node_error({"actuator.host=lab-target"}).find("actuator.host: host: expected a dotted IPv4 address"),
      std::string::npos)
      << speedgoat_node_error({"actuator.host=lab-target"});
}

}  // namespace
}  // namespace rpsd::scenarios
