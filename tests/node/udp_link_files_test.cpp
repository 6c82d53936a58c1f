// The controller link as a node file and an emulator file state it: version 2 is the default
// and needs a key file; a key file that group or others may read is refused naming the file,
// the line and the key that names it; version 1 only when the file says so, and then the
// start line warns that the link is unauthenticated; the emulator names its node.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rpsd/node/udp_controller_actuator.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"

namespace rpsd::node {
namespace {

namespace fs = std::filesystem;

class LinkFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_);
    std::ofstream(key_, std::ios::binary) << std::string(32, 'k');
    ::chmod(key_.c_str(), 0600);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path node_file(const std::string& link) {
    const fs::path file = dir_ / "node.yaml";
    std::ofstream(file) << "node: {test_id: 7, site_id: 1, mode: lock_step, control_rate_hz: 1024}\n"
                           "dds: {domain_id: 0}\n"
                           "actuator:\n"
                           "  kind: udp_controller\n"
                           "  channels: 1\n"
                           "  host: 127.0.0.1\n"
                           "  port: 45999\n"
                        << link << "  rig: {stroke_m: 0.25, force_n: 1.0e6, velocity_m_per_s: 1.0}\n";
    return file;
  }
  fs::path emulator_file(const std::string& link) {
    const fs::path file = dir_ / "emulator.yaml";
    std::ofstream(file) << "udp:\n"
                           "  port: 45999\n"
                           "  node_host: 127.0.0.1\n"
                           "  node_port: 45998\n"
                        << link
                        << "actuator:\n"
                           "  channels: 1\n"
                           "  servo: {kind: ideal_delay, delay_s: 0.01, rig: {stroke_m: 0.25, force_n: 1.0e6, "
                           "velocity_m_per_s: 1.0}}\n";
    return file;
  }
  template <typename Load>
  static std::string error_of(Load load) {
    try {
      load();
    } catch (const scenarios::ConfigError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_ = fs::temp_directory_path() / ("rpsd-udp-files-" + std::to_string(::getpid()));
  fs::path key_ = dir_ / "lab.key";
};

TEST_F(LinkFiles, AKeyFileOthersCanReadIsRefusedNamingTheFileAndTheKey) {
  ::chmod(key_.c_str(), 0644);
  const fs::path node = node_file("  key_file: lab.key\n");
  const std::string n = error_of([&] { (void)scenarios::load_servo_node(node); });
  EXPECT_EQ(n.rfind(node.string() + ":8:", 0), 0u) << n;  // the line of key_file
  EXPECT_NE(n.find("actuator.key_file: " + key_.string() + ": the key file's mode is 0644"), std::string::npos) << n;
  EXPECT_NE(n.find("chmod 600"), std::string::npos) << n;
  const fs::path emulator = emulator_file("  key_file: lab.key\n");
  const std::string e = error_of([&] { (void)scenarios::load_controller_emulator(emulator); });
  EXPECT_EQ(e.rfind(emulator.string() + ":5:", 0), 0u) << e;
  EXPECT_NE(e.find("udp.key_file: " + key_.string() + ": the key file's mode is 0644"), std::string::npos) << e;
  ::chmod(key_.c_str(), 0600);
  EXPECT_EQ(error_of([&] { (void)scenarios::load_servo_node(node); }), "");
  EXPECT_EQ(error_of([&] { (void)scenarios::load_controller_emulator(emulator); }), "");
}

TEST_F(LinkFiles, VersionTwoIsTheDefaultAndNeedsAKeyFile) {
  const std::string n = error_of([&] { (void)scenarios::load_servo_node(node_file("")); });
  EXPECT_NE(n.find("actuator.key_file: protocol version 2 (the default) needs the key"), std::string::npos) << n;
  const std::string e = error_of([&] { (void)scenarios::load_controller_emulator(emulator_file("")); });
  EXPECT_NE(e.find("udp.key_file: protocol version 2 (the default) needs the key"), std::string::npos) << e;
  const auto setup = scenarios::load_servo_node(node_file("  key_file: lab.key\n"));
  const auto& udp = std::get<UdpControllerParameters>(setup.actuator);
  EXPECT_EQ(udp.protocol_version, 2);
  EXPECT_EQ(udp.key.size(), 32u);
  EXPECT_NE(describe_link(udp).find("protocol version 2 (HMAC-SHA-256, key " + key_.string() + ")"), std::string::npos);
  EXPECT_EQ(scenarios::load_controller_emulator(emulator_file("  key_file: lab.key\n")).udp.key.size(), 32u);
}

TEST_F(LinkFiles, VersionOneOnlyWhenTheFileSaysSoAndThenTheStartLineWarns) {
  const auto setup = scenarios::load_servo_node(node_file("  protocol_version: 1\n"));
  const auto& udp = std::get<UdpControllerParameters>(setup.actuator);
  EXPECT_EQ(udp.protocol_version, 1);
  EXPECT_NE(describe_link(udp).find("WARNING: the link is unauthenticated"), std::string::npos) << describe_link(udp);
  // A key with version 1 would suggest a protection that is not there.
  const std::string n =
      error_of([&] { (void)scenarios::load_servo_node(node_file("  protocol_version: 1\n  key_file: lab.key\n")); });
  EXPECT_NE(n.find("actuator.key_file: protocol version 1 authenticates nothing"), std::string::npos) << n;
  EXPECT_EQ(scenarios::load_controller_emulator(emulator_file("  protocol_version: 1\n")).udp.protocol_version, 1);
}

TEST_F(LinkFiles, TheEmulatorFileNamesItsNode) {
  const fs::path file = dir_ / "no-node.yaml";
  std::ofstream(file) << "udp: {port: 45999, key_file: lab.key}\n"
                         "actuator: {channels: 1, servo: {kind: ideal_delay, delay_s: 0.01, rig: {stroke_m: 0.25, "
                         "force_n: 1.0e6, velocity_m_per_s: 1.0}}}\n";
  const std::string e = error_of([&] { (void)scenarios::load_controller_emulator(file); });
  EXPECT_NE(e.find("udp.node_host"), std::string::npos) << e;
  const auto setup = scenarios::load_controller_emulator(emulator_file("  key_file: lab.key\n"));
  EXPECT_EQ(setup.udp.node_host, "127.0.0.1");
  EXPECT_EQ(setup.udp.node_port, 45998);
}

}  // namespace
}  // namespace rpsd::node
