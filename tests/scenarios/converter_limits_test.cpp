// Converters never blind a limit (docs/safety.md): wherever a file gives a plant converters and
// limits (a scenario, a servo node, a site server), every limit on a reading, stated or the
// rig's, must lie strictly inside what the reading's A/D converter can represent; otherwise the
// file is refused naming the limit's key and the converter's. Every plant kind alike.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::scenarios {
namespace {

std::filesystem::path source(const char* path) { return testing::source_dir() / path; }
const std::filesystem::path kBenchmark = source("examples/scenarios/rths-benchmark-sample-controller-case-1.yaml");

std::vector<Override> overrides(std::initializer_list<const char*> texts) {
  std::vector<Override> o;
  for (const char* t : texts) o.push_back(parse_override(t));
  return o;
}

template <class Load>
std::string config_error_of(Load load) {
  try {
    load();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string study_config_error(const std::filesystem::path& file, std::initializer_list<const char*> texts) {
  return config_error_of([&] { (void)load_study(file, overrides(texts)); });
}

// The case of issue 25: a force A/D saturating at 2 V reads at most 131071 steps of 4/2^18 V
// times 1096 N/V = 2191.98 N (and -131072 steps below zero), below the 3000 N limit.
TEST(ConverterLimits, AForceLimitItsConverterCannotReadIsRefusedNamingBothKeys) {
  const std::string e = study_config_error(
      kBenchmark, {"experimental.0.limits.max_force_n=3000", "servo.converters.force.units_per_volt=1096",
                   "servo.converters.force.bits=18", "servo.converters.force.saturation_v=2"});
  EXPECT_NE(e.find("experimental[0].limits.max_force_n: 3000 N is not strictly inside what servo.converters.force "
                   "can read, -2192 to 2191.98 N"),
            std::string::npos)
      << e;
  // Strictly inside: a limit below the rail stands.
  EXPECT_EQ(study_config_error(kBenchmark,
                               {"experimental.0.limits.max_force_n=2000", "servo.converters.force.units_per_volt=1096",
                                "servo.converters.force.bits=18", "servo.converters.force.saturation_v=2"}),
            "");
}

// No limit stated: the rig's 8.9 kN is the limit, held to the same rule, so a nonsense range
// (1e-300 V) is refused, and so is a displacement A/D of +/-3.9 mm on the 7 mm stroke.
TEST(ConverterLimits, TheRigsDefaultLimitIsHeldToTheSameRule) {
  const std::string e = study_config_error(kBenchmark, {"servo.converters.force.saturation_v=1e-300"});
  EXPECT_NE(e.find("experimental[0].limits.max_force_n: not stated, so the rig's 8900 N, which is not strictly inside "
                   "what servo.converters.force can read"),
            std::string::npos)
      << e;
  const std::string d = study_config_error(kBenchmark, {"servo.converters.displacement.units_per_volt=7.89e-3",
                                                        "servo.converters.displacement.saturation_v=0.5"});
  EXPECT_NE(d.find("experimental[0].limits.max_stroke_m: not stated, so the rig's 0.007 m"), std::string::npos) << d;
  EXPECT_NE(d.find("servo.converters.displacement"), std::string::npos) << d;
  // As shipped, the released chain: the measurements have no rail at all.
  EXPECT_EQ(study_config_error(kBenchmark, {}), "");
}

// Every plant kind behind converters: the paper's servo model, an ideal delay, a transfer
// function, a servo loop. A 1 kN force A/D cannot read any of their rigs' force capacity.
TEST(ConverterLimits, EveryPlantKindIsHeldToTheRule) {
  const char* scenarios[] = {"examples/scenarios/elcentro-sdof.yaml", "tests/coordinator/data/sdof-free-vibration.yaml",
                             "examples/scenarios/rths-benchmark-case1.yaml",
                             "examples/scenarios/rths-benchmark-sample-controller-case-1.yaml"};
  for (const char* scenario : scenarios) {
    const std::string e = study_config_error(
        source(scenario), {"servo.converters.force.units_per_volt=1000", "servo.converters.force.saturation_v=1"});
    EXPECT_NE(e.find("experimental[0].limits.max_force_n: not stated, so the rig's"), std::string::npos)
        << scenario << ": " << e;
    EXPECT_NE(e.find("servo.converters.force can read, -1000 to "), std::string::npos) << scenario << ": " << e;
  }
}

// The range a dry run compares its predictions with (servo::reading_ranges_of): a chain in
// volts, 18 bits over +/-10 V, reads to its rails; the shipped benchmark's released chain has
// none on either measurement.
TEST(ConverterLimits, TheReadingRangesOfAPlantAreItsConvertersRails) {
  const auto study =
      load_study(kBenchmark,
                 overrides({"servo.converters.force.units_per_volt=1096", "servo.converters.force.saturation_v=10",
                            "servo.converters.force.bits=18", "servo.converters.displacement.units_per_volt=7.89e-3",
                            "servo.converters.displacement.saturation_v=10", "servo.converters.displacement.bits=18"}));
  const auto& t = std::get<hybrid_test::TestConfig>(study.study);
  const servo::ReadingRanges r = servo::reading_ranges_of(t.plant);
  const double step_v = 20.0 / std::ldexp(1.0, 18);
  EXPECT_EQ(r.force_n.high, 131071.0 * step_v * 1096.0);
  EXPECT_EQ(r.force_n.low, -10.0 * 1096.0);  // -2^17 steps: exactly the saturation's -10 V
  EXPECT_EQ(r.displacement_m.high, 131071.0 * step_v * 7.89e-3);
  const auto shipped = load_study(kBenchmark);
  EXPECT_FALSE(servo::reading_ranges_of(std::get<hybrid_test::TestConfig>(shipped.study).plant).force_n.bounded());
  const auto paper = load_study(source("examples/scenarios/elcentro-sdof.yaml"));
  EXPECT_FALSE(servo::reading_ranges_of(std::get<hybrid_test::TestConfig>(paper.study).plant).force_n.bounded());
}

// A servo node file: its limits are the only ones there, so each (stated or the rig's) must
// be readable through the simulated actuator's converters.
TEST(ConverterLimits, AServoNodeFileIsHeldToTheRule) {
  const auto node = source("examples/nodes/rths-benchmark-site.yaml");
  const std::string e = config_error_of([&] {
    (void)load_servo_node(node,
                          overrides({"limits.max_force_n=[3000]", "actuator.servo.converters.force.saturation_v=2"}));
  });
  EXPECT_NE(
      e.find("limits[0].max_force_n: 3000 N is not strictly inside what actuator.servo.converters.force can read"),
      std::string::npos)
      << e;
  const std::string d = config_error_of(
      [&] { (void)load_servo_node(node, overrides({"actuator.servo.converters.displacement.saturation_v=0.005"})); });
  EXPECT_NE(d.find("limits[0].max_stroke_m: not stated, so the rig's 0.007 m"), std::string::npos) << d;
  EXPECT_NE(d.find("actuator.servo.converters.displacement"), std::string::npos) << d;
  // As shipped it loads (the released chain: no rail on the measurements), and its node knows
  // the rails given and the rig its measurements must stay inside.
  EXPECT_FALSE(load_servo_node(node).node.rails[0].force_n.bounded());
  const auto setup = load_servo_node(node, overrides({"actuator.servo.converters.force.saturation_v=9000"}));
  EXPECT_EQ(setup.node.rails[0].force_n.high, 9000.0);
  EXPECT_EQ(setup.node.rig[0].stroke_m, 0.007);
}

TEST(ConverterLimits, ASiteServerFileIsHeldToTheRule) {
  const auto site = source("tests/scenarios/data/reference/site-server.yaml");
  const std::string e = config_error_of([&] {
    (void)load_site_server(
        site, overrides({"servo.converters.force.units_per_volt=100", "servo.converters.force.saturation_v=1"}));
  });
  EXPECT_NE(e.find("experimental[0].limits.max_force_n: not stated, so the rig's 156000 N"), std::string::npos) << e;
  EXPECT_NE(e.find("servo.converters.force can read, -100 to 100 N"), std::string::npos) << e;
  EXPECT_EQ(config_error_of([&] { (void)load_site_server(site, {}); }), "");
}

}  // namespace
}  // namespace rpsd::scenarios
