// `monte_carlo:` in a scenario: each run is the file with the drawn values set, read and
// checked in full before anything runs; errors name the key and the run.
#include <gtest/gtest.h>

#include <filesystem>

#include "../servo/paper_rig.h"
#include "rpsd/hybrid_test/monte_carlo.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::scenarios {
namespace {

std::filesystem::path case1() {
  return testing::source_dir() / "examples/scenarios/rths-benchmark-sample-controller-case-1.yaml";
}

TEST(MonteCarloFile, EachRunIsTheScenarioWithItsDrawnPlantAndItsOwnNoiseSeed) {
  const auto file = load_study(case1(), {parse_override("monte_carlo.runs=4")});
  ASSERT_TRUE(file.monte_carlo);
  const hybrid_test::MonteCarloConfig& mc = *file.monte_carlo;
  ASSERT_EQ(mc.parameters.size(), 4u);
  EXPECT_EQ(mc.parameters[0].key_path, "servo.rths_benchmark_model.a3_per_s");
  EXPECT_EQ(mc.parameters[0].nominal, 3.3);  // the file's value is the mean
  EXPECT_EQ(mc.parameters[3].spread, 5.0e4);
  EXPECT_EQ(mc.parameters[3].key_path, "experimental.0.specimen.stiffness_n_per_m");
  EXPECT_EQ(mc.parameters[3].also_key_paths,
            std::vector<std::string>{"servo.rths_benchmark_model.specimen_stiffness_n_per_m"});
  ASSERT_EQ(file.sweep_cases.size(), 4u);
  const auto draws = hybrid_test::draw_monte_carlo(mc);
  for (std::size_t run = 0; run < 4; ++run) {
    SCOPED_TRACE(run);
    EXPECT_EQ(file.sweep_values[run], draws[run]);
    const auto& plant = std::get<servo::FeedbackControlledPlantParameters>(file.sweep_cases[run].plant);
    // The run's own k_e: in G_xu's constant term through (s + a3) k_e, and in the load cell,
    // and the same draw in the partition (also_keys): the specimen the numerical part leaves out.
    EXPECT_EQ(plant.plant.specimen_stiffness_n_per_m, draws[run][3]);
    EXPECT_EQ(plant.converters.displacement.seed, mc.seed + run + 1 + 1);  // seed + run, then + 1 for displacement
    EXPECT_EQ(file.sweep_cases[run].experimental[0].dof.specimen_stiffness_estimate_n_per_m, draws[run][3]);
  }
  EXPECT_NE(file.sweep_values[0][0], file.sweep_values[1][0]);
}

TEST(MonteCarloFile, AKeyThatIsNotANumberOrARunThatCannotBeBuiltIsNamed) {
  try {
    (void)load_study(case1(), {parse_override("monte_carlo.parameters.0.key=servo.no_such_key")});
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("servo.no_such_key is not a number"), std::string::npos) << e.what();
  }
  try {
    // a3 drawn about -1000 with sigma 1: G_xu has a pole in the right half-plane in every run.
    (void)load_study(case1(), {parse_override("servo.rths_benchmark_model.a3_per_s=-1000")});
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("monte_carlo run 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unstable"), std::string::npos) << e.what();
  }
  try {
    (void)load_study(case1(), {parse_override("sweep=[{key: servo.plant_rate_hz, values: [16384]}]")});
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("either sweep or monte_carlo"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::scenarios
