// Parameter files: the shipped one loads with its documented values; bad ones fail with
// file:line:column and the key path.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_parameters_file.h"

namespace rpsd::scenarios {
namespace {

std::string paper_file_text() {
  std::ifstream in(testing::source_dir() / "examples/servo/paper-mts-244.yaml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class BadParameterFile : public ::testing::Test {
 protected:
  // Writes the paper's file with `from` replaced by `to` and returns the loader's message.
  std::string error_for(const std::string& from, const std::string& to) {
    std::string text = paper_file_text();
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    path_ = std::filesystem::temp_directory_path() /
            ("rpsd-bad-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml");
    std::ofstream(path_) << text;
    try {
      load_servo_parameters(path_);
    } catch (const ConfigError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error for " << to;
    return {};
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::filesystem::path path_;
};

TEST(ServoParametersFile, LoadsThePaperRig) {
  const auto p = testing::paper_rig();
  EXPECT_EQ(p.name, "paper-mts-244");
  EXPECT_DOUBLE_EQ(p.specimen.mass_kg, 7080.0);
  EXPECT_DOUBLE_EQ(p.specimen.stiffness.initial_n_per_m, 700.8e3);
  EXPECT_DOUBLE_EQ(p.specimen.stiffness.secondary_n_per_m, 350.4e3);
  EXPECT_DOUBLE_EQ(p.specimen.stiffness.change_displacement_m, 0.0254);
  EXPECT_DOUBLE_EQ(p.specimen.friction_force_n, 95.7);
  EXPECT_DOUBLE_EQ(p.specimen.damping_ratio, 0.011);
  EXPECT_DOUBLE_EQ(p.controller.derivative_gain_s, 2.0e-4);
  EXPECT_TRUE(p.flow.nonlinear_flow_gain);
  EXPECT_TRUE(p.flow.load_pressure_effect);
  EXPECT_DOUBLE_EQ(p.plant_rate_hz, 8192.0);
}

TEST_F(BadParameterFile, NegativeMassNamesLineAndKey) {
  const std::string message = error_for("mass_kg: 7080 ", "mass_kg: -7080 ");
  EXPECT_TRUE(std::regex_search(
      message, std::regex(R"(\.yaml:\d+:\d+: specimen\.mass_kg: expected a number > 0 and <= 1e\+09, got "-7080")")))
      << message;
}

TEST_F(BadParameterFile, MissingKeyNamesKeyPath) {
  const std::string message = error_for("  piston_area_m2: 7.536e-3", "");
  EXPECT_TRUE(
      std::regex_search(message, std::regex(R"(\.yaml:\d+:\d+: actuator\.piston_area_m2: required key is missing)")))
      << message;
}

TEST_F(BadParameterFile, UnknownKeyIsRejectedWithItsLine) {
  const std::string message = error_for("  derivative_gain_s: 2.0e-4", "  derivativ_gain_s: 2.0e-4");
  // The line of the misspelt key in the shipped file (line numbers are 1-based).
  std::istringstream text(paper_file_text());
  int line = 0;
  for (std::string s; std::getline(text, s);) {
    ++line;
    if (s.find("derivative_gain_s: 2.0e-4") != std::string::npos) break;
  }
  EXPECT_NE(message.find(".yaml:" + std::to_string(line) + ":3: controller.derivativ_gain_s: unknown key"),
            std::string::npos)
      << message;
}

TEST_F(BadParameterFile, TextWhereANumberBelongs) {
  const std::string message = error_for("bulk_modulus_pa: 1.3e9", "bulk_modulus_pa: stiff");
  EXPECT_NE(message.find("actuator.bulk_modulus_pa: expected a number, got \"stiff\""), std::string::npos) << message;
}

TEST_F(BadParameterFile, YamlSyntaxErrorNamesLine) {
  const std::string message = error_for("controller:", "controller: [");
  EXPECT_TRUE(std::regex_search(message, std::regex(R"(\.yaml:\d+:\d+: YAML syntax error)"))) << message;
}

TEST_F(BadParameterFile, PlantRateTooLowForTheSpoolLoop) {
  const std::string message = error_for("plant_rate_hz: 8192", "plant_rate_hz: 1000");
  EXPECT_NE(message.find("plant_rate_hz: too low"), std::string::npos) << message;
}

TEST(ServoParametersFile, MissingFileIsAClearError) {
  try {
    load_servo_parameters("/nonexistent/rig.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/rig.yaml: does not exist");
  }
}

}  // namespace
}  // namespace rpsd::scenarios
