// A nees_plugin node file and a plugin site emulator file as the readers take them: the
// shipped examples read as they say; every bad value is refused naming the file, the line
// and the key; OpenFresco's set-parameter is sent unless the file says [none].
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/plugin_site_file.h"
#include "rpsd/scenarios/servo_node_file.h"

namespace rpsd::scenarios {
namespace {

namespace fs = std::filesystem;
namespace np = node::nees_plugin;

const std::string kNodeHead =
    "node: {test_id: 29, site_id: 1, mode: lock_step, control_rate_hz: 100}\ndds: {domain_id: 0}\n"
    "actuator:\n  kind: nees_plugin\n";
const std::string kSiteServo =
    "  servo: {kind: ideal_delay, delay_s: 0, rig: {stroke_m: 0.25, force_n: 1.0e6, velocity_m_per_s: 1.0}}\n";

// What a reader says of a file: its error, or "accepted".
template <auto Load>
std::string verdict(const fs::path& file) try {
  (void)Load(file, {});
  return "accepted";
} catch (const ConfigError& e) {
  return e.what();
}

class PluginFiles : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path written(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // A node file whose actuator keys (below kind) are `actuator`, from line 5.
  fs::path node_file(const std::string& actuator) { return written("node.yaml", kNodeHead + actuator); }
  // A site file whose plugin_site keys (below port and node_host) are `site`, from line 4.
  fs::path site_file(const std::string& site, const std::string& channels = "1") {
    return written("site.yaml", "plugin_site:\n  port: 44000\n  node_host: 127.0.0.1\n" + site +
                                    "actuator:\n  channels: " + channels + "\n" + kSiteServo);
  }
  // The file is refused at `line`, with `key` (and what follows) in the message.
  template <auto Load>
  static void expect_refused(const fs::path& file, int line, const std::string& key) {
    const std::string error = verdict<Load>(file);
    EXPECT_EQ(error.rfind(file.string() + ":" + std::to_string(line) + ":", 0), 0u) << error;
    EXPECT_NE(error.find(key), std::string::npos) << error;
  }

  fs::path dir_ = fs::temp_directory_path() / ("rpsd-plugin-files-" + std::to_string(::getpid()));
};

const std::string kRig = "  rig: {stroke_m: 0.25, force_n: 1.0e6, velocity_m_per_s: 1.0}\n";

TEST_F(PluginFiles, TheShippedNodeFileReadsAsItSays) {
  const node::ServoNodeSetup setup = load_servo_node(testing::source_dir() / "examples/nodes/plugin-site-node.yaml");
  const auto& p = std::get<node::NeesPluginParameters>(setup.actuator);
  EXPECT_EQ(p.port, 44000);
  EXPECT_EQ(p.session_name, "OpenFresco");
  ASSERT_EQ(p.parameters.size(), 1u);
  EXPECT_EQ(p.parameters[0], (std::vector<std::string>{"OPFTransaction", "nstep", "1"}));
  ASSERT_EQ(p.channel_map.size(), 1u);
  EXPECT_EQ(p.channel_map[0].control_point, "MDL-00-01");
  EXPECT_EQ(p.channel_map[0].axis, np::Axis::kX);
  EXPECT_EQ(p.channel_map[0].displacement_per_si, 1000.0);
  EXPECT_EQ(p.channel_map[0].force_per_si, 0.001);
  EXPECT_EQ(p.reply_timeout_s, 30.0);
  EXPECT_EQ(setup.node.limits[0].max_stroke_m, 0.05);
  EXPECT_EQ(setup.node.limits[0].max_velocity_m_per_s, 0.3);  // the rig's, left out
}

TEST_F(PluginFiles, TheShippedSiteFileReadsAsItSays) {
  const node::PluginSiteEmulatorSetup setup =
      load_plugin_site_emulator(testing::source_dir() / "examples/nodes/plugin-site-emulator.yaml");
  EXPECT_EQ(setup.site.port, 44000);
  ASSERT_EQ(setup.site.channels(), 1);
  EXPECT_EQ(setup.site.control_points[0].name, "MDL-00-01");
  EXPECT_EQ(setup.site.control_points[0].dofs[0].upper_limit, 40.0);
  EXPECT_EQ(setup.site.fault, node::PluginSiteFault::kNone);
  EXPECT_EQ(setup.initial_displacement_m, std::vector<double>{0.0});
}

TEST_F(PluginFiles, DefaultsAreOpenFrescosAndNoneSendsNoParameter) {
  const fs::path plain = node_file(
      "  channels: 1\n  host: 127.0.0.1\n  port: 44000\n  channel_map: [{control_point: MDL-00-01, axis: x}]\n" + kRig);
  const auto p = std::get<node::NeesPluginParameters>(load_servo_node(plain).actuator);
  EXPECT_EQ(p.session_name, "OpenFresco");
  ASSERT_EQ(p.parameters.size(), 1u);
  EXPECT_EQ(p.parameters[0], (std::vector<std::string>{"OPFTransaction", "nstep", "1"}));
  EXPECT_EQ(p.channel_map[0].motion, np::Motion::kTranslation);
  EXPECT_EQ(p.channel_map[0].displacement_per_si, 1.0);
  const fs::path none = node_file(
      "  channels: 1\n  host: 127.0.0.1\n  port: 44000\n  parameters: [none]\n"
      "  channel_map: [{control_point: MDL-00-01, axis: x}]\n" +
      kRig);
  EXPECT_TRUE(std::get<node::NeesPluginParameters>(load_servo_node(none).actuator).parameters.empty());
}

TEST_F(PluginFiles, ABadNodeFileIsRefusedAtItsLineAndKey) {
  const std::string head = "  channels: 2\n  host: 127.0.0.1\n  port: 44000\n";  // lines 5-7
  {
    const fs::path f = node_file(head + "  channel_map: [{control_point: A, axis: x}]\n" + kRig);
    expect_refused<load_servo_node>(f, 8, "actuator.channel_map: one entry per channel (2), got 1");
  }
  {
    const fs::path f = node_file(
        head + "  channel_map:\n    - {control_point: A, axis: x}\n    - {control_point: A, axis: x}\n" + kRig);
    expect_refused<load_servo_node>(f, 10, "actuator.channel_map[1].axis: channel 0 is already A x");
  }
  {
    const fs::path f = node_file(
        head + "  channel_map:\n    - {control_point: A, axis: w}\n    - {control_point: B, axis: x}\n" + kRig);
    expect_refused<load_servo_node>(f, 9, "actuator.channel_map[0].axis");
  }
  {
    const fs::path f = node_file(
        head + "  channel_map:\n    - {control_point: \"A B\", axis: x}\n    - {control_point: B, axis: x}\n" + kRig);
    expect_refused<load_servo_node>(f, 9, "actuator.channel_map[0].control_point");
  }
  {
    const fs::path f = node_file(head +
                                 "  channel_map:\n    - {control_point: A, axis: x, force_per_si: 0}\n"
                                 "    - {control_point: B, axis: x}\n" +
                                 kRig);
    expect_refused<load_servo_node>(f, 9, "actuator.channel_map[0].force_per_si");
  }
  {
    const fs::path f = node_file(head + "  channel_map: [{control_point: A, axis: x}, {control_point: B, axis: y}]\n");
    expect_refused<load_servo_node>(f, 4, "actuator.rig: a hardware node must state its rig");
  }
  {
    const fs::path f = node_file(
        head + "  reply_timeout_s: 0\n  channel_map: [{control_point: A, axis: x}, {control_point: B, axis: y}]\n" +
        kRig);
    expect_refused<load_servo_node>(f, 8, "actuator.reply_timeout_s");
  }
  {
    const fs::path f = node_file(
        "  channels: 1\n  host: 127.0.0.256\n  port: 44000\n"
        "  channel_map: [{control_point: A, axis: x}]\n" +
        kRig);
    expect_refused<load_servo_node>(f, 6, "actuator.host");
  }
}

TEST_F(PluginFiles, ABadSiteFileIsRefusedAtItsLineAndKey) {
  {
    const fs::path f = site_file("  control_points:\n    - name: A\n      dofs: [{axis: x, limits: [5, -5]}]\n");
    expect_refused<load_plugin_site_emulator>(
        f, 6, "plugin_site.control_points[0].dofs[0].limits: give [lowest, highest], lowest first");
  }
  {
    const fs::path f = site_file("  control_points:\n    - name: A\n      dofs: [{axis: x, limits: [-5, 5]}]\n", "2");
    expect_refused<load_plugin_site_emulator>(f, 8, "actuator.channels: one per dof of the control points (1)");
  }
  {
    const fs::path f = site_file(
        "  control_points:\n    - name: A\n      dofs: [{axis: x, limits: [-5, 5]}]\n"
        "  fault: {kind: crash, after_steps: 3}\n");
    expect_refused<load_plugin_site_emulator>(f, 7, "plugin_site.fault.kind");
  }
  {
    const fs::path f =
        site_file("  node_port: 4\n  control_points:\n    - name: A\n      dofs: [{axis: x, limits: [-5, 5]}]\n");
    expect_refused<load_plugin_site_emulator>(f, 4, "plugin_site.node_port: unknown key");
  }
}

}  // namespace
}  // namespace rpsd::scenarios
