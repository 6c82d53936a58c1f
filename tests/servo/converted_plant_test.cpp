// Any plant behind a channel's converters (servo.converters): the D/A's quantisation and limit
// on the command, the A/D's codes and noise on the readings, read from a plant section of any
// kind; without converters the plant is not wrapped.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rpsd/scenarios/yaml_reader.h"
#include "rpsd/servo/converted_plant.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::servo {
namespace {

PlantConfig read_servo_on_specimen(const std::string& yaml) {
  scenarios::MappingReader reader(scenarios::parse_yaml_text(yaml, "servo.yaml"), "servo.yaml", "servo");
  return read_plant_config(reader, 1.0e5);
}

const std::string kIdealDelay =
    "kind: ideal_delay\ndelay_s: 0\nrig: {stroke_m: 0.1, force_n: 1.0e6, velocity_m_per_s: 1}\n";

TEST(ConvertedPlant, AnIdealActuatorBehindConvertersReadsTheirCodesAndStopsAtTheDaLimit) {
  // 10 bits over +/-1 V (D/A) and 11 over +/-2 V (A/D) at 10 mm/V: both steps are 2/1024 V =
  // 19.53 um; the D/A's +/-1 V is +/-10 mm of command, inside the A/D's 20 mm.
  const PlantConfig config =
      read_servo_on_specimen(kIdealDelay +
                             "converters: {command: {units_per_volt: 0.01, saturation_v: 1, bits: 10},\n"
                             "  displacement: {units_per_volt: 0.01, saturation_v: 2, bits: 11},\n"
                             "  force: {units_per_volt: 1000, noise_rms_v: 0.01}}\n");
  const auto plant = make_plant(config);
  ASSERT_NE(dynamic_cast<ConvertedPlant*>(plant.get()), nullptr);
  const double step = 2.0 / 1024.0 * 0.01;
  plant->reset(0.0);
  plant->advance(0.0, 0.00123, 1e-3);
  const PlantMeasurement m = plant->measure();
  EXPECT_NEAR(m.displacement_m, std::round(0.00123 / step) * step, 1e-15);  // a code, the nearest
  EXPECT_NE(m.force_n, 1.0e5 * m.displacement_m);                           // 10 N of noise on the load cell
  EXPECT_NEAR(m.force_n, 1.0e5 * m.displacement_m, 6.0 * 10.0);
  EXPECT_FALSE(m.valve_saturated);
  plant->advance(0.00123, 0.05, 1e-3);  // beyond the D/A's 10 mm
  EXPECT_TRUE(plant->measure().valve_saturated);
  EXPECT_LE(plant->measure().displacement_m, 0.01 + 1e-15);
  EXPECT_GT(plant->measure().displacement_m, 0.0099);
}

TEST(ConvertedPlant, WithoutConvertersThePlantIsNotWrappedAndABadOneIsNamed) {
  EXPECT_EQ(dynamic_cast<ConvertedPlant*>(make_plant(read_servo_on_specimen(kIdealDelay)).get()), nullptr);
  try {
    (void)read_servo_on_specimen(kIdealDelay + "converters: {force: {units_per_volt: 1000, bits: 12}}\n");
    FAIL() << "a converter without a range was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("converters.force"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("servo.yaml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::servo
