// The pre-test checks' pieces: a converter's rail is where the converter really clamps, a
// margin is what is left to a bound, and a mode above the actuator's cut-off is named with the
// key of the masses.

#include "rpsd/studies/pretest_checks.h"
#include "rpsd/studies/converter_rails.h"

#include <gtest/gtest.h>

#include <cmath>

#include "rpsd/servo/signal_converter.h"

namespace rpsd::studies {
namespace {

// The rail is the largest magnitude SignalConverter puts out, on either side.
void expect_rail_is_where_it_clamps(const servo::SignalConverterParameters& p) {
  servo::SignalConverter converter(p);
  const double rail = converter_rail(p);
  const double big = 1e6 * std::abs(p.units_per_volt);
  EXPECT_DOUBLE_EQ(rail, std::min(std::abs(converter.convert(big)), std::abs(converter.convert(-big))))
      << "bits " << p.bits << ", saturation " << p.saturation_v << " V, full scale " << p.full_scale_v << " V";
}

TEST(ConverterRails, TheRailIsWhereTheConverterClamps) {
  servo::SignalConverterParameters p;
  p.units_per_volt = 2.54e-3;  // 10 V for 25.4 mm
  p.saturation_v = 10.0;
  expect_rail_is_where_it_clamps(p);  // saturation only: 25.4 mm
  EXPECT_DOUBLE_EQ(converter_rail(p), 25.4e-3);
  p.bits = 16;
  expect_rail_is_where_it_clamps(p);  // a 16-bit converter of +/-10 V: one step inside at the top
  EXPECT_LT(converter_rail(p), 25.4e-3);
  p.full_scale_v = 12.0;  // a converter wider than the saturation: its largest step inside it
  expect_rail_is_where_it_clamps(p);
  p.saturation_v = 0.0;  // no saturation: the converter's own range
  expect_rail_is_where_it_clamps(p);
  p.units_per_volt = 1096.0;  // a load cell: N
  p.saturation_v = 9.0;
  expect_rail_is_where_it_clamps(p);
}

TEST(ConverterRails, NoVoltageStageNoRail) {
  EXPECT_TRUE(std::isinf(converter_rail({})));
  servo::SignalConverterParameters noise_only;
  noise_only.units_per_volt = 1e-3;
  noise_only.noise_rms_v = 0.01;
  EXPECT_TRUE(std::isinf(converter_rail(noise_only)));
}

TEST(PretestChecks, MarginIsWhatIsLeftToTheBound) {
  const LimitMargin stroke = margin_to("stroke", -24.7e-3, 25.4e-3);
  EXPECT_NEAR(stroke.margin, 1.0 - 24.7 / 25.4, 1e-12);
  EXPECT_TRUE(stroke.low());  // 3 %: below the 10 % that is warned about
  EXPECT_FALSE(stroke.reached());
  EXPECT_FALSE(margin_to("force", 10e3, 30e3).low());
  EXPECT_TRUE(margin_to("rail", 1.0, 1.0, true).reached());
  EXPECT_DOUBLE_EQ(margin_to("none", 5.0, std::numeric_limits<double>::infinity()).margin, 1.0);
  EXPECT_EQ(describe(stroke, 1e3, "mm"), "stroke 24.7 / 25.4 mm: margin 3 % (below 10 %)");
}

TEST(PretestChecks, ModesAboveTheCutOffAreNamedWithTheMassKey) {
  const auto warnings = modes_beyond_bandwidth({1.2, 36.0, 80.0}, 1.959, "structure.mass_kg");
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("mode 2 at 36 Hz"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("mode 3 at 80 Hz"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("cut-off frequency of 1.959 Hz"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("structure.mass_kg"), std::string::npos) << warnings[1];
  EXPECT_TRUE(modes_beyond_bandwidth({1.2, 1.9}, 1.959, "structure.mass_kg").empty());
}

}  // namespace
}  // namespace rpsd::studies
