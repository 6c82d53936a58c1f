// The servo loop of a channel around a plant from the controller's output, against
// independent answers: the benchmark's G_xu from its parameters against the published closed
// loop, the PI loop against the continuous closed loop's frequency response, the specimen's
// force against k + j c w - m w^2, and the converters inside the loop.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "rpsd/scenarios/yaml_reader.h"
#include "rpsd/servo/benchmark_transfer_system.h"
#include "rpsd/servo/feedback_controlled_plant.h"
#include "rpsd/servo/harmonic_fit.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/servo/simulated_frequency_response.h"
#include "rths_benchmark_plant.h"

namespace rpsd::servo {
namespace {

constexpr double kRateHz = 4096.0;

BenchmarkTransferSystem nominal() { return rpsd::testing::rths_benchmark_nominal(); }

FeedbackControlledPlantParameters sample_controller_loop() {
  FeedbackControlledPlantParameters p;
  const BenchmarkTransferSystem b = nominal();
  p.plant.transfer_function = b.transfer_function();
  p.plant.specimen_stiffness_n_per_m = b.specimen_stiffness_n_per_m;
  p.plant.plant_rate_hz = 32768.0;
  p.controller = PidGains{2.0, 95.0, 0.0, 0.0};  // the benchmark's sample G_C = 2 + 95/s
  return p;
}

TEST(BenchmarkTransferSystem, ItsParametersGiveThePublishedClosedLoopTransferFunction) {
  // The reference sheet's closed loop: 2.18385e13 / [29.13 1.25906e4 8.42178e6 2.32849e9
  // 5.43547e11 2.16756e13], published to six digits.
  const TransferFunction g = nominal().transfer_function();
  const double published[] = {2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13};
  ASSERT_EQ(g.denominator.degree(), 5);
  ASSERT_EQ(g.numerator.degree(), 0);
  for (int i = 0; i <= 5; ++i) EXPECT_NEAR(g.denominator.coefficient(i) / published[i], 1.0, 1e-5) << "s^" << i;
  EXPECT_NEAR(g.numerator.coefficient(0) / 2.18385e13, 1.0, 1e-5);
}

TEST(FeedbackControlledPlant, ThePiLoopFollowsTheContinuousClosedLoopFrequencyResponse) {
  // T = G_C G / (1 + G_C G). The discrete loop acts at the start of each period on the target
  // for its end (one period early, e^{s dt}) and the displacement measured then, and holds its
  // output over the period (half a period of lag inside the loop, e^{-s dt / 2}): to first
  // order in w dt, e^{s dt} G_C G e^{-s dt/2} / (1 + G_C G e^{-s dt/2}).
  FeedbackControlledPlant plant(sample_controller_loop());
  const TransferFunction g = nominal().transfer_function();
  for (double f : {1.0, 5.0, 10.0, 20.0}) {
    SCOPED_TRACE(f);
    const std::complex<double> s(0.0, 2.0 * std::numbers::pi * f);
    const std::complex<double> gc = 2.0 + 95.0 / s, open = gc * g(s) * std::exp(-s / (2.0 * kRateHz));
    const std::complex<double> expected = std::exp(s / kRateHz) * open / (1.0 + open);
    const std::complex<double> continuous = gc * g(s) / (1.0 + gc * g(s));
    const std::complex<double> measured = simulated_frequency_response(plant, SineTest{1e-3, f, kRateHz, 2.0, 4});
    // Measured 6e-5 and 0.002 degrees at 20 Hz (second order in w dt).
    EXPECT_NEAR(std::abs(measured) / std::abs(expected), 1.0, 2e-4);
    EXPECT_NEAR(std::arg(measured / expected) * 180.0 / std::numbers::pi, 0.0, 0.01);
    // And the continuous loop itself within the first-order terms: 1 % and w dt in degrees.
    EXPECT_NEAR(std::abs(measured) / std::abs(continuous), 1.0, 0.015);
    EXPECT_LT(std::abs(std::arg(measured / continuous)), 2.0 * std::numbers::pi * f / kRateHz);
  }
}

TEST(FeedbackControlledPlant, TheIntegralActionHoldsATargetExactlyThoughTheStaticGainIsNotOne) {
  // G_xu(0) = 1.0075: without the controller a held command reads 0.75 % high.
  FeedbackControlledPlant plant(sample_controller_loop());
  for (int k = 0; k < 4 * 4096; ++k) plant.advance(2e-3, 2e-3, 1.0 / kRateHz);
  EXPECT_NEAR(plant.measure().displacement_m, 2e-3, 2e-3 * 1e-6);
  EXPECT_FALSE(plant.measure().valve_saturated);
  // reset() holds a displacement with the integral carrying x / G(0): nothing moves.
  plant.reset(1e-3);
  plant.advance(1e-3, 1e-3, 1.0 / kRateHz);
  EXPECT_NEAR(plant.measure().displacement_m, 1e-3, 1e-12);
}

TEST(FeedbackControlledPlant, TheSpecimensDampingAndMassEnterTheMeasuredForce) {
  // Steady sine: F = (k + j c w - m w^2) X to first order in w dt, X the displacement's phasor.
  FeedbackControlledPlantParameters p = sample_controller_loop();
  const BenchmarkTransferSystem b = nominal();
  p.plant.specimen_damping_n_s_per_m = b.specimen_damping_n_s_per_m * 100.0;  // large enough to see
  p.plant.specimen_mass_kg = b.specimen_mass_kg;
  FeedbackControlledPlant plant(p);
  const double f = 8.0, w = 2.0 * std::numbers::pi * f, dt = 1.0 / kRateHz;
  std::vector<double> phase, x, force;
  plant.reset(0.0);
  for (int k = 1; k <= 3 * 4096; ++k) {
    plant.advance(0.0, 1e-3 * std::sin(w * k * dt), dt);
    if (k > 4096) {
      phase.push_back(w * k * dt);
      x.push_back(plant.measure().displacement_m);
      force.push_back(plant.measure().force_n);
    }
  }
  const HarmonicFit xf = fit_harmonic(phase, x), ff = fit_harmonic(phase, force);
  const std::complex<double> xp = std::polar(xf.amplitude, xf.phase_rad), fp = std::polar(ff.amplitude, ff.phase_rad);
  // The inertial part is the acceleration averaged over the period, (v(t) - v(t - dt)) / dt:
  // j w (1 - e^{-j w dt}) / dt X, which tends to -w^2 X.
  const std::complex<double> jw(0.0, w);
  const std::complex<double> mean_acceleration = jw * (1.0 - std::exp(-jw * dt)) / dt;
  const std::complex<double> expected = (b.specimen_stiffness_n_per_m + jw * p.plant.specimen_damping_n_s_per_m +
                                         b.specimen_mass_kg * mean_acceleration) *
                                        xp;
  EXPECT_NEAR(std::abs(fp) / std::abs(expected), 1.0, 1e-6);
  EXPECT_NEAR(std::arg(fp / expected), 0.0, 1e-6);
  // The phase of the force leads the displacement's by atan(c w / (k - m w^2)).
  EXPECT_GT(std::arg(fp / xp), 0.01);
}

TEST(FeedbackControlledPlant, TheConvertersSitInsideTheLoopAndTheirNoiseRepeatsFromItsSeed) {
  FeedbackControlledPlantParameters p = sample_controller_loop();
  p.converters.command = {7.89e-3, 0.0, 3.8, 18, 0.0, 11};
  p.converters.displacement = {7.89e-3, 0.002, 3.8, 18, 0.0, 12};
  p.converters.force = {1096.0, 0.002, 3.8, 18, 0.0, 13};
  const double step_m = 7.6 / 262144.0 * 7.89e-3;
  FeedbackControlledPlant plant(p);
  std::vector<double> first;
  for (int k = 0; k < 4096; ++k) {
    plant.advance(1e-3, 1e-3, 1.0 / kRateHz);
    const double x = plant.measure().displacement_m;
    first.push_back(x);
    ASSERT_NEAR(x / step_m, std::round(x / step_m), 1e-6) << k;  // an A/D code
  }
  // The noise is 0.002 V x 7.89 mm/V = 15.8 um RMS around the held 1 mm.
  double sum2 = 0.0;
  for (std::size_t k = 2048; k < first.size(); ++k) sum2 += (first[k] - 1e-3) * (first[k] - 1e-3);
  const double rms = std::sqrt(sum2 / 2048.0);
  EXPECT_GT(rms, 0.8 * 15.78e-6);
  EXPECT_LT(rms, 1.2 * 15.78e-6);
  plant.reset(0.0);
  for (int k = 0; k < 4096; ++k) plant.advance(1e-3, 1e-3, 1.0 / kRateHz);
  plant.reset(0.0);
  for (std::size_t k = 0; k < 100; ++k) {
    plant.advance(1e-3, 1e-3, 1.0 / kRateHz);
    ASSERT_EQ(plant.measure().displacement_m, first[k]) << k;
  }
}

TEST(FeedbackControlledPlant, ATargetBeyondTheDaRangeSaturatesTheValveWithoutWindingUp) {
  // The D/A's +/-3.8 V at 7.89 mm/V: the controller's output stops at 29.98 mm; the plant
  // settles at G(0) times it and the saturation is reported (the run-away guard's input).
  FeedbackControlledPlantParameters p = sample_controller_loop();
  p.converters.command = {7.89e-3, 0.0, 3.8, 0, 0.0, 1};
  FeedbackControlledPlant plant(p);
  for (int k = 0; k < 2 * 4096; ++k) plant.advance(0.05, 0.05, 1.0 / kRateHz);
  EXPECT_TRUE(plant.measure().valve_saturated);
  const double g0 = nominal().transfer_function().static_gain();
  EXPECT_NEAR(plant.measure().displacement_m, g0 * 3.8 * 7.89e-3, 1e-7);
  // Back to 10 mm. An integral that had wound up over the 2 s at an error of ~20 mm would hold
  // 95 x 0.02 x 2 = 3.8 m and keep the valve open for about 2 s more; the clamped one lets the
  // loop settle within a quarter of a second.
  for (int k = 0; k < 1024; ++k) plant.advance(0.01, 0.01, 1.0 / kRateHz);
  EXPECT_NEAR(plant.measure().displacement_m, 0.01, 1e-4);
  EXPECT_FALSE(plant.measure().valve_saturated);
}

PlantConfig read_servo(const std::string& yaml) {
  scenarios::MappingReader reader(scenarios::parse_yaml_text(yaml, "servo.yaml"), "servo.yaml", "servo");
  return read_plant_config(reader, 0.0);
}

TEST(FeedbackControlledPlant, ReadsTheBenchmarkFormAndNamesAPlantGivenTwice) {
  const std::string model =
      "rths_benchmark_model: {gain: 1.0261, a1_beta0: 2.1283e13, a2: 4.2297e6, a3_per_s: 3.3, beta1_per_s: 425, "
      "beta2_per_s2: 9.9976e4, specimen_mass_kg: 29.13, specimen_damping_n_s_per_m: 114.22, "
      "specimen_stiffness_n_per_m: 1.19e6}\n";
  const PlantConfig config =
      read_servo("kind: feedback_controlled\n" + model +
                 "controller: {proportional_gain: 2, integral_gain_per_s: 95}\n"
                 "converters: {seed: 5, command: {units_per_volt: 7.89e-3, saturation_v: 3.8, bits: 18},\n"
                 "  force: {units_per_volt: 1096, noise_rms_v: 0.002}}\n"
                 "rig: {stroke_m: 0.007, force_n: 8900, velocity_m_per_s: 0.3}\n");
  const auto& p = std::get<FeedbackControlledPlantParameters>(config);
  EXPECT_EQ(p.plant.specimen_stiffness_n_per_m, 1.19e6);
  EXPECT_EQ(p.plant.specimen_mass_kg, 29.13);
  EXPECT_EQ(p.controller->integral_per_s, 95.0);
  EXPECT_EQ(p.converters.command.bits, 18);
  EXPECT_EQ(p.converters.force.seed, 7u);  // each converter its own stream from the seed
  EXPECT_EQ(p.converters.displacement.units_per_volt, 0.0);
  EXPECT_EQ(envelope_of(config).stroke_m, 0.007);
  EXPECT_EQ(specimen_stiffness_of(config), 1.19e6);
  try {
    read_servo("kind: feedback_controlled\n" + model + "numerator_descending: [1]\ndenominator_descending: [1, 1]\n" +
               "rig: {stroke_m: 0.007, force_n: 8900, velocity_m_per_s: 0.3}\n");
    FAIL() << "a plant given twice was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("either"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("servo.yaml"), std::string::npos) << e.what();
  }
}

TEST(FeedbackControlledPlant, ADerivativeFilterShorterThanHalfThePeriodIsRefusedBeforeTheTest) {
  FeedbackControlledPlantParameters p = sample_controller_loop();
  p.controller = PidGains{2.0, 95.0, 1e-3, 1e-4};  // Tf = 0.1 ms < T/2 = 0.122 ms at 4096 Hz
  EXPECT_NO_THROW(p.validate_for_period(1.0 / 2048.0 / 4.0));
  try {
    check_control_period(p, 1.0 / kRateHz);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("controller"), std::string::npos) << e.what();
  }
}

// The loop's own signals through their converters (the benchmark's released chain rounds the
// reference and the error): a reference below half a step rounds to zero and the loop holds
// still, where without the converter it follows; the same for the error.
TEST(FeedbackControlledPlant, TheReferenceAndErrorConvertersActInsideTheLoop) {
  const auto settle = [](FeedbackControlledPlantParameters p, double target_m) {
    FeedbackControlledPlant plant(p);
    for (int k = 0; k < 4096; ++k) plant.advance(target_m, target_m, 1.0 / kRateHz);
    return plant.measure().displacement_m;
  };
  SignalConverterParameters coarse;  // 1 mm steps, +/-5 mm
  coarse.units_per_volt = 1.0;
  coarse.saturation_v = 5e-3;
  coarse.bits = 4;
  coarse.full_scale_v = 8e-3;
  const double target = 0.4e-3;  // below half a 1 mm step
  EXPECT_NEAR(settle(sample_controller_loop(), target), target, 1e-6);
  for (SignalConverterParameters ChannelConverters::*which :
       {&ChannelConverters::reference, &ChannelConverters::error}) {
    FeedbackControlledPlantParameters p = sample_controller_loop();
    p.converters.*which = coarse;
    EXPECT_EQ(settle(p, target), 0.0);
    // A target beyond the rail is clamped: the loop settles at most at the rail's 5 mm.
    if (which == &ChannelConverters::reference) {
      EXPECT_NEAR(settle(p, 6e-3), 5e-3, 1e-6);
    }
  }
}

TEST(FeedbackControlledPlant, OnlyAServoLoopHasReferenceAndErrorConverters) {
  try {
    (void)read_servo(
        "kind: transfer_function\nnumerator_descending: [1]\ndenominator_descending: [0.01, 1]\n"
        "rig: {stroke_m: 0.007, force_n: 8900, velocity_m_per_s: 0.3}\n"
        "converters: {error: {units_per_volt: 1, saturation_v: 3.8}}\n");
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("converters"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("only a servo loop"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::servo
