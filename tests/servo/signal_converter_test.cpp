// SignalConverter against the definitions of its stages: saturation at +/- V, a mid-tread
// converter of step 2 FS / 2^bits (uniform error of RMS q / sqrt(12) over a fine ramp), white
// Gaussian noise of the given RMS, repeatable seeds, NaN through, and no allocation per call.
#include "rpsd/servo/signal_converter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "allocation_counter.h"

namespace rpsd::servo {
namespace {

constexpr double kLvdtMPerV = 7.89e-3;
constexpr double kLoadCellNPerV = 1096.0;

SignalConverterParameters displacement_adc() {
  SignalConverterParameters p;
  p.units_per_volt = kLvdtMPerV;
  p.saturation_v = 3.8;
  p.bits = 18;
  return p;
}

TEST(SignalConverter, PassesThroughWithEveryStageOff) {
  SignalConverter c(SignalConverterParameters{});
  for (const double x : {0.0, -0.0, 1.0, -1.0, 3.25e-7, -0.0123, 1e6, -1e6, 1e300}) {
    EXPECT_EQ(c.convert(x), x);
    EXPECT_FALSE(c.saturated());
  }
  EXPECT_EQ(c.step_units(), 0.0);
}

TEST(SignalConverter, SaturatesAtTheVoltageLimit) {
  SignalConverterParameters p;
  p.units_per_volt = kLvdtMPerV;
  p.saturation_v = 3.8;
  SignalConverter c(p);
  EXPECT_EQ(c.convert(0.05), 3.8 * 7.89e-3);
  EXPECT_TRUE(c.saturated());
  EXPECT_EQ(c.convert(-0.05), -3.8 * 7.89e-3);
  EXPECT_TRUE(c.saturated());
  EXPECT_NEAR(c.convert(0.01), 0.01, 1e-15);  // 1.27 V: inside
  EXPECT_FALSE(c.saturated());
  EXPECT_NEAR(c.convert(-0.029), -0.029, 1e-15);  // -3.68 V: inside
  EXPECT_FALSE(c.saturated());
}

TEST(SignalConverter, QuantisesToTheNearestStepWithUniformError) {
  SignalConverter c(displacement_adc());
  const double step_m = 7.6 / std::ldexp(1.0, 18) * 7.89e-3;
  ASSERT_NEAR(c.step_units(), step_m, 1e-12 * step_m);

  // A fine ramp across zero, about 23 samples a step, its spacing incommensurate with the step.
  const int n = 100000;
  const double start_m = -2000.37 * step_m;
  const double spacing_m = 4321.7 * step_m / (n - 1);
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = start_m + i * spacing_m;
    const double y = c.convert(x);
    ASSERT_FALSE(c.saturated()) << i;
    const double steps = y / step_m;
    ASSERT_LE(std::abs(steps - std::round(steps)), 1e-9 * std::max(1.0, std::abs(steps))) << i << " " << y;
    const double e = y - x;
    ASSERT_LE(std::abs(e), 0.5 * step_m * (1.0 + 1e-9)) << i;
    sum += e;
    sum_sq += e * e;
  }
  const double rms = std::sqrt(sum_sq / n);
  EXPECT_NEAR(rms, step_m / std::sqrt(12.0), 0.02 * step_m / std::sqrt(12.0));
  EXPECT_LE(std::abs(sum / n), 0.01 * step_m);
}

TEST(SignalConverter, IsMidTread) {
  SignalConverter c(displacement_adc());
  const double q = c.step_units();
  EXPECT_EQ(c.convert(0.0), 0.0);
  EXPECT_EQ(c.convert(0.4 * q), 0.0);
  EXPECT_EQ(c.convert(-0.4 * q), 0.0);
  EXPECT_NEAR(c.convert(0.6 * q), q, 1e-9 * q);
  EXPECT_NEAR(c.convert(-0.6 * q), -q, 1e-9 * q);
  EXPECT_NEAR(c.convert(7.3 * q), 7.0 * q, 1e-9 * q);
}

TEST(SignalConverter, QuantisedValueStaysInsideTheSaturationAndTheConverterRange) {
  {  // full scale = saturation: two's-complement codes -2^17 .. 2^17 - 1 of 3.8 / 2^17 V
    SignalConverter c(displacement_adc());
    const double q_v = 3.8 / std::ldexp(1.0, 17);
    EXPECT_DOUBLE_EQ(c.convert(0.05), (std::ldexp(1.0, 17) - 1.0) * q_v * kLvdtMPerV);
    EXPECT_TRUE(c.saturated());
    EXPECT_DOUBLE_EQ(c.convert(-0.05), -3.8 * kLvdtMPerV);
    EXPECT_TRUE(c.saturated());
  }
  {  // converter wider than the saturation: 4 bits over +/- 10 V, step 1.25 V, clamp at 4.4 V
    SignalConverterParameters p;
    p.units_per_volt = 1.0;
    p.saturation_v = 4.4;
    p.bits = 4;
    p.full_scale_v = 10.0;
    SignalConverter c(p);
    EXPECT_EQ(c.step_units(), 1.25);
    EXPECT_EQ(c.convert(100.0), 3.75);  // 4.4 V is 3.52 steps: it would round to 4 * 1.25 = 5 V > 4.4 V
    EXPECT_TRUE(c.saturated());
    EXPECT_EQ(c.convert(-4.5), -3.75);
    EXPECT_TRUE(c.saturated());
    EXPECT_EQ(c.convert(3.0), 2.5);  // 2.4 steps
    EXPECT_FALSE(c.saturated());
  }
  {  // converter narrower than the saturation: 4 bits over +/- 2 V, step 0.25 V, codes -8 .. 7
    SignalConverterParameters p;
    p.units_per_volt = 1.0;
    p.saturation_v = 3.8;
    p.bits = 4;
    p.full_scale_v = 2.0;
    SignalConverter c(p);
    EXPECT_EQ(c.convert(3.0), 1.75);
    EXPECT_TRUE(c.saturated());
    EXPECT_EQ(c.convert(-3.0), -2.0);
    EXPECT_TRUE(c.saturated());
  }
}

TEST(SignalConverter, NoiseIsWhiteGaussianOfTheGivenRms) {
  SignalConverterParameters p;
  p.units_per_volt = kLoadCellNPerV;
  p.noise_rms_v = 0.002;
  p.seed = 12345;
  SignalConverter c(p);
  const double sigma_n = 0.002 * 1096.0;
  const double force_n = 500.0;
  const int n = 200000;
  std::vector<double> e(n);
  for (int i = 0; i < n; ++i) e[i] = c.convert(force_n) - force_n;

  double sum = 0.0, sum_sq = 0.0;
  int beyond_two_sigma = 0;
  for (const double v : e) {
    sum += v;
    sum_sq += v * v;
    if (std::abs(v) > 2.0 * sigma_n) ++beyond_two_sigma;
  }
  const double mean = sum / n;
  EXPECT_LE(std::abs(mean), 4.0 * sigma_n / std::sqrt(static_cast<double>(n)));
  EXPECT_NEAR(std::sqrt(sum_sq / n), sigma_n, 0.01 * sigma_n);

  double lag0 = 0.0, lag1 = 0.0;
  for (int i = 0; i < n; ++i) {
    lag0 += (e[i] - mean) * (e[i] - mean);
    if (i + 1 < n) lag1 += (e[i] - mean) * (e[i + 1] - mean);
  }
  EXPECT_LT(std::abs(lag1 / lag0), 0.02);
  // P(|Z| > 2) = erfc(2 / sqrt 2) = 4.55 %
  EXPECT_NEAR(static_cast<double>(beyond_two_sigma) / n, std::erfc(std::sqrt(2.0)), 0.003);
}

TEST(SignalConverter, NoiseComesBeforeTheSaturationAndTheConverter) {
  SignalConverterParameters p = displacement_adc();
  p.noise_rms_v = 0.002;  // about 70 steps of 29 uV
  SignalConverter c(p);
  const double step_m = c.step_units();
  const double top_m = (std::ldexp(1.0, 17) - 1.0) * 3.8 / std::ldexp(1.0, 17) * kLvdtMPerV;
  int distinct = 0;
  double previous = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const double y = c.convert(0.01);
    const double steps = y / step_m;
    ASSERT_LE(std::abs(steps - std::round(steps)), 1e-9 * std::abs(steps)) << i << " " << y;
    distinct += i > 0 && y != previous;
    previous = y;
    // Well beyond the saturation the noise cannot show: the top code every time.
    ASSERT_EQ(c.convert(0.05), top_m) << i;
    ASSERT_EQ(c.convert(-0.05), -3.8 * kLvdtMPerV) << i;
  }
  EXPECT_GT(distinct, 900);  // the noise is there
}

std::vector<double> sequence(SignalConverter& c, int n) {
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) out[i] = c.convert(1e-5 * i);  // up to 0.01 m, 1.27 V: never clamped
  return out;
}

TEST(SignalConverter, SeedsRepeatAndDiffer) {
  SignalConverterParameters p = displacement_adc();
  p.noise_rms_v = 0.01;
  p.seed = 42;
  SignalConverter a(p), b(p);
  p.seed = 43;
  SignalConverter other(p);
  // An odd count leaves the normal distribution holding the second value of a pair.
  const int n = 1001;
  const std::vector<double> first = sequence(a, n);
  EXPECT_EQ(sequence(b, n), first);
  const std::vector<double> different = sequence(other, n);
  int equal = 0;
  for (int i = 0; i < n; ++i) equal += different[i] == first[i];
  EXPECT_LT(equal, n / 10);
  // The sequence goes on; 1001 + 500 draws again leave a value held.
  EXPECT_NE(sequence(a, 500), std::vector<double>(first.begin(), first.begin() + 500));
  a.reseed();
  EXPECT_EQ(sequence(a, n), first);
}

TEST(SignalConverter, NonFiniteInputComesOutUnchanged) {
  SignalConverterParameters p = displacement_adc();
  p.noise_rms_v = 0.002;
  SignalConverter c(p);
  EXPECT_TRUE(std::isnan(c.convert(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_FALSE(c.saturated());
  EXPECT_EQ(c.convert(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.convert(-std::numeric_limits<double>::infinity()), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isfinite(c.convert(0.001)));
}

void expect_rejected(const SignalConverterParameters& p, const std::string& key) {
  try {
    p.validate();
    ADD_FAILURE() << "accepted; expected a complaint about " << key;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
  EXPECT_THROW(SignalConverter{p}, std::invalid_argument) << key;
}

TEST(SignalConverter, ValidateNamesTheBadKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const SignalConverterParameters good = displacement_adc();
  EXPECT_NO_THROW(good.validate());
  EXPECT_NO_THROW(SignalConverterParameters{}.validate());

  SignalConverterParameters p = good;
  p.units_per_volt = -1.0;
  expect_rejected(p, "units_per_volt");
  p.units_per_volt = nan;
  expect_rejected(p, "units_per_volt");
  p = good;
  p.noise_rms_v = -0.001;
  expect_rejected(p, "noise_rms_v");
  p.noise_rms_v = inf;
  expect_rejected(p, "noise_rms_v");
  p = good;
  p.saturation_v = -3.8;
  expect_rejected(p, "saturation_v");
  p.saturation_v = nan;
  expect_rejected(p, "saturation_v");
  p = good;
  p.full_scale_v = -10.0;
  expect_rejected(p, "full_scale_v");
  p.full_scale_v = inf;
  expect_rejected(p, "full_scale_v");
  p = good;
  p.bits = -1;
  expect_rejected(p, "bits");
  p.bits = 31;
  expect_rejected(p, "bits");
  p.bits = 30;
  EXPECT_NO_THROW(p.validate());
  p = good;
  p.saturation_v = 0.0;  // and full_scale_v 0: no range for the converter
  expect_rejected(p, "bits");
  p = good;
  p.bits = 0;
  p.full_scale_v = 10.0;
  expect_rejected(p, "full_scale_v");

  SignalConverterParameters unscaled;
  unscaled.noise_rms_v = 0.002;
  expect_rejected(unscaled, "noise_rms_v");
  unscaled = {};
  unscaled.saturation_v = 3.8;
  expect_rejected(unscaled, "saturation_v");
  unscaled = {};
  unscaled.bits = 16;
  unscaled.full_scale_v = 10.0;
  expect_rejected(unscaled, "bits");
}

// range() is what a limit is checked against (docs/safety.md): exactly the readings a clamped
// input gives, on either side, for saturation alone, a converter inside its saturation band,
// a two's-complement converter without saturation (one code more below zero), and nothing.
TEST(SignalConverter, ItsRangeIsExactlyTheReadingOfAClampedInput) {
  SignalConverterParameters saturation;
  saturation.units_per_volt = kLoadCellNPerV;
  saturation.saturation_v = 2.0;
  SignalConverterParameters full_scale;
  full_scale.units_per_volt = kLoadCellNPerV;
  full_scale.bits = 12;
  full_scale.full_scale_v = 10.0;
  SignalConverterParameters tiny = displacement_adc();
  tiny.saturation_v = 1e-300;
  for (const SignalConverterParameters& p : {saturation, displacement_adc(), full_scale, tiny}) {
    const ConverterRange r = p.range();
    SignalConverter c(p);
    EXPECT_EQ(c.convert(1e12), r.high);
    EXPECT_TRUE(r.at_rail(c.convert(1e12)));
    EXPECT_EQ(c.convert(-1e12), r.low);
    EXPECT_TRUE(r.at_rail(c.convert(-1e12)));
    EXPECT_FALSE(r.at_rail(c.convert(0.5 * r.high)));
    EXPECT_TRUE(r.represents(0.5 * r.rail_magnitude()));
    EXPECT_FALSE(r.represents(r.rail_magnitude()));  // a limit on the rail is not inside it
  }
  EXPECT_EQ(saturation.range().high, 2.0 * kLoadCellNPerV);
  EXPECT_EQ(full_scale.range().high, 2047.0 * 20.0 / 4096.0 * kLoadCellNPerV);
  EXPECT_EQ(full_scale.range().low, -2048.0 * 20.0 / 4096.0 * kLoadCellNPerV);
  EXPECT_EQ(full_scale.range().rail_magnitude(), full_scale.range().high);
  EXPECT_LT(tiny.range().high, 1e-300);  // 1e-300 V: no limit a test could have is inside it
  EXPECT_FALSE(tiny.range().represents(1e-3));
  const ConverterRange none = SignalConverterParameters{}.range();
  EXPECT_FALSE(none.bounded());
  EXPECT_FALSE(none.at_rail(1e300));
  EXPECT_TRUE(none.represents(1e300));
}

TEST(SignalConverter, CounterSeesAllocations) {
  rpsd::testing::begin_counting_allocations();
  auto* p = new int(3);
  rpsd::testing::keep(p);
  delete p;
  EXPECT_EQ(rpsd::testing::end_counting_allocations().operator_new, 1);
}

TEST(SignalConverter, ConvertAndReseedAllocateNothing) {
  SignalConverterParameters p = displacement_adc();
  p.noise_rms_v = 0.002;
  SignalConverter c(p);
  double sink = 0.0;
  rpsd::testing::begin_counting_allocations();
  for (int i = 0; i < 10000; ++i) {
    sink += c.convert(0.03 * std::sin(0.001 * i));
    if (i % 1000 == 0) c.reseed();
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace rpsd::servo
