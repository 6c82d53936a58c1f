// `rpsd validate --json` says what the text says: one reading of the file gives both.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "rpsd/commands/validate_report.h"

namespace rpsd::commands {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(RPSD_TEST_SOURCE_DIR) / "examples";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ValidateFile, TheJsonOverviewIsTheTextAndTheKindIsTheFiles) {
  const struct {
    std::filesystem::path file;
    const char* kind;
  } files[] = {{kExamples / "scenarios/elcentro-sdof.yaml", "rpsd_test"},
               {kExamples / "scenarios/elcentro-sdof-compensation-sweep.yaml", "sweep"},
               {kExamples / "scenarios/rths-benchmark-sample-controller-case-1.yaml", "monte_carlo"},
               {kExamples / "scenarios/paper-fig8-delay-compensation.yaml", "study"},
               {kExamples / "nodes/bridge-pier-site-1.yaml", "servo_node"}};
  for (const auto& f : files) {
    std::ostringstream text;
    const nlohmann::json report = validate_file(f.file, {}, text);
    EXPECT_EQ(report["kind"], f.kind) << f.file;
    std::vector<std::string> printed = lines_of(text.str());
    ASSERT_FALSE(printed.empty());
    EXPECT_NE(printed.front().find(": ok"), std::string::npos) << printed.front();
    printed.erase(printed.begin());
    EXPECT_EQ(report["overview"].get<std::vector<std::string>>(), printed) << f.file;
  }
}

TEST(ValidateFile, ATestsNumbersAreItsOverviews) {
  std::ostringstream text;
  const nlohmann::json report =
      validate_file(kExamples / "scenarios/elcentro-sdof.yaml", {{"ground_motion.trim.end_s", "2", "--set #1"}}, text);
  const nlohmann::json& test = report["test"];
  EXPECT_EQ(test["steps"], 2048);
  EXPECT_EQ(test["dofs"], 1);
  // sqrt(700.8e3 / 7080) / 2 pi = 1.5834 Hz, the paper's SDOF on its springs.
  EXPECT_NEAR(test["structure_modes"][0]["frequency_hz"].get<double>(), 1.5834, 1e-4);
  EXPECT_EQ(test["channels"][0]["limits"]["max_stroke_m"], 0.127);
  EXPECT_TRUE(test["channels"][0]["converter_rails"]["force_n"].is_null());
}

}  // namespace
}  // namespace rpsd::commands
