// A scenario's held_forces: actuators of experimental sites that hold a force in force control
// (mixed control). What the file says reaches TestConfig::held_forces, and what cannot be held
// safely is refused at its key with the file and line (exit 2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/transport/messages.h"

namespace rpsd::scenarios {
namespace {

const std::filesystem::path kAxialLoadColumn = testing::source_dir() / "examples/scenarios/column-axial-load.yaml";

hybrid_test::TestConfig axial_load_column(std::vector<Override> overrides = {}) {
  return std::get<hybrid_test::TestConfig>(load_study(kAxialLoadColumn, overrides).study);
}

void refused_overrides(const std::vector<std::string>& overrides, const std::string& words) {
  std::vector<Override> parsed;
  for (const auto& o : overrides) parsed.push_back(parse_override(o));
  EXPECT_THAT([&] { (void)axial_load_column(parsed); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr(words)))
      << overrides.back();
}

std::string held(const std::string& name, double force_n = -10.0e3) {
  return "{site: 1, name: " + name + ", force_n: " + std::to_string(force_n) +
         ", max_force_rate_n_per_s: 10.0e3, specimen_stiffness_n_per_m: 700.8e3}";
}

TEST(HeldForcesFile, TheExampleHoldsItsAxialLoadOnSiteOne) {
  const hybrid_test::TestConfig t = axial_load_column();
  ASSERT_EQ(t.held_forces.size(), 1u);
  const hybrid_test::HeldForce& h = t.held_forces[0];
  EXPECT_EQ(h.site_id, 1u);
  EXPECT_EQ(h.name, "axial");
  EXPECT_DOUBLE_EQ(h.force_n, -30.0e3);
  EXPECT_DOUBLE_EQ(h.max_force_rate_n_per_s, 10.0e3);
  EXPECT_DOUBLE_EQ(h.specimen_stiffness_n_per_m, 700.8e3);
  EXPECT_DOUBLE_EQ(h.limits.max_force_n, 40.0e3);
  EXPECT_DOUBLE_EQ(h.limits.max_stroke_m, 0.08);
  EXPECT_FALSE(std::isfinite(h.limits.max_force_error_n));  // as read: the rig's default comes later
  EXPECT_NEAR(hybrid_test::held_force_limits(h, servo::envelope_of(t.plant)).max_force_error_n,
              0.1 * servo::envelope_of(t.plant).force_n, 1e-6);
  EXPECT_EQ(t.experimental.size(), 1u);  // not a DOF of the structure
  // A test without the key holds none.
  EXPECT_TRUE(std::get<hybrid_test::TestConfig>(
                  load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml").study)
                  .held_forces.empty());
}

TEST(HeldForcesFile, EachRequiredKeyIsRequired) {
  for (const char* key : {"site", "name", "force_n", "max_force_rate_n_per_s", "specimen_stiffness_n_per_m"}) {
    std::string entry =
        "{site: 1, name: axial, force_n: -10.0e3, max_force_rate_n_per_s: 10.0e3, "
        "specimen_stiffness_n_per_m: 700.8e3}";
    entry = std::regex_replace(entry, std::regex(std::string(key) + ": [^,}]*(, )?"), "");
    refused_overrides({"held_forces=[" + entry + "]"}, "held_forces[0]." + std::string(key));
  }
}

TEST(HeldForcesFile, ARateOrAStiffnessThatIsNotPositiveIsRefused) {
  refused_overrides({"held_forces.0.max_force_rate_n_per_s=0"}, "held_forces[0].max_force_rate_n_per_s");
  refused_overrides({"held_forces.0.max_force_rate_n_per_s=-1.0e3"}, "held_forces[0].max_force_rate_n_per_s");
  refused_overrides({"held_forces.0.specimen_stiffness_n_per_m=0"}, "held_forces[0].specimen_stiffness_n_per_m");
  refused_overrides({"held_forces.0.force_n=.nan"}, "held_forces[0].force_n");
}

TEST(HeldForcesFile, ANameIsAShortUniqueIdentifier) {
  refused_overrides({"held_forces.0.name=Axial load"}, "held_forces[0].name: 'Axial load' is not a short identifier");
  refused_overrides({"held_forces.0.name=" + std::string(33, 'a')}, "held_forces[0].name");
  refused_overrides({"held_forces=[" + held("axial") + ", " + held("axial") + "]"},
                    "held_forces[1].name: 'axial' names held_forces[0] too");
  EXPECT_EQ(axial_load_column({parse_override("held_forces=[" + held("axial") + ", " + held("axial_2") + "]")})
                .held_forces.size(),
            2u);
}

TEST(HeldForcesFile, AForceBeyondItsLimitOrTheRigIsRefused) {
  refused_overrides({"held_forces.0.force_n=-50.0e3"},
                    "held_forces[0].force_n: |-50000| N is beyond limits.max_force_n");
  // Without a stated limit: the rig's force capacity (156 kN).
  refused_overrides({"held_forces=[" + held("axial", -160.0e3) + "]"}, "held_forces[0].force_n");
}

TEST(HeldForcesFile, ALimitBeyondTheRigIsRefusedAtItsKey) {
  refused_overrides({"held_forces.0.limits.max_force_n=200.0e3"},
                    "held_forces[0].limits.max_force_n: 200000 is beyond the rig's force capacity");
  refused_overrides({"held_forces.0.limits.max_stroke_m=0.2"},
                    "held_forces[0].limits.max_stroke_m: 0.2 is beyond the rig's");
  refused_overrides({"held_forces.0.limits.max_force_error_n=160.0e3"}, "held_forces[0].limits.max_force_error_n");
  refused_overrides({"held_forces.0.limits.max_force_error_n=0"}, "held_forces[0].limits.max_force_error_n");
}

TEST(HeldForcesFile, TheSiteMustBeAnExperimentalSiteWithActuators) {
  refused_overrides({"held_forces.0.site=7"}, "held_forces[0].site: site 7 has no experimental[] channel");
  // An OpenSees site is numerical: no actuator to hold a force.
  EXPECT_THAT(
      [] {
        (void)load_study(testing::source_dir() / "examples/opensees/three-storey-split.yaml",
                         {parse_override("held_forces=[{site: 2, name: axial, force_n: -1.0e3, "
                                         "max_force_rate_n_per_s: 1.0e3, specimen_stiffness_n_per_m: 1.0e6}]")});
      },
      ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("held_forces[0].site: site 2 is an OpenSees site")));
}

TEST(HeldForcesFile, InThisProcessThePlantMustHaveAForceLoopOverDdsTheNodeSays) {
  const std::string without =
      "servo.parameters=" + (testing::source_dir() / "examples/servo/paper-mts-244.yaml").string();
  refused_overrides({without}, "held_forces[0]: site 1's actuators are simulated in this process");
  refused_overrides({without}, "no force loop");
  // Over DDS the node's file says whether its channel can hold a force (it refuses otherwise).
  EXPECT_EQ(axial_load_column({parse_override(without), parse_override("transport.kind=dds")}).held_forces.size(), 1u);
}

TEST(HeldForcesFile, ExperimentalAndHeldChannelsTogetherFitTheLink) {
  std::string list;
  for (int k = 0; k < transport::kMaxChannels; ++k) {
    if (k > 0) list += ", ";
    list += held(std::string(1, static_cast<char>('a' + k)));
  }
  std::ostringstream words;
  words << "held_forces[" << transport::kMaxChannels - 1 << "].site: more than " << transport::kMaxChannels
        << " link channels in all";
  refused_overrides({"held_forces=[" + list + "]"}, words.str());
}

TEST(HeldForcesFile, ARefusalNamesTheFileAndLine) {
  // The example with its file names absolute and its force beyond its limit, in a file of its own.
  std::ifstream in(kAxialLoadColumn);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string examples = (testing::source_dir() / "examples").string();
  text = std::regex_replace(text, std::regex(R"(\.\./\.\./)"), testing::source_dir().string() + "/");
  text = std::regex_replace(text, std::regex(R"(\.\./servo/)"), examples + "/servo/");
  text = std::regex_replace(text, std::regex(R"(force_n: -30\.0e3)"), "force_n: -45.0e3");
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "rpsd-held-forces-line.yaml";
  std::ofstream(file) << text;
  int line = 0, n = 0;
  for (std::size_t at = 0, next; (next = text.find('\n', at)) != std::string::npos; at = next + 1) {
    ++n;
    if (text.compare(at, next - at, "    force_n: -45.0e3                     # N, compression") == 0) line = n;
  }
  ASSERT_GT(line, 0);
  EXPECT_THAT([&] { (void)load_study(file); },
              ::testing::ThrowsMessage<ConfigError>(
                  ::testing::AllOf(::testing::HasSubstr(file.string() + ":" + std::to_string(line) + ":"),
                                   ::testing::HasSubstr("held_forces[0].force_n: |-45000| N is beyond"))));
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace rpsd::scenarios
