// The ideal pure-delay plant and the transfer-function plant against closed forms and the
// RTHS benchmark's published frequency response.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/simulated_frequency_response.h"
#include "rpsd/servo/transfer_function_plant.h"

namespace rpsd::servo {
namespace {

TEST(PureDelayPlant, ReproducesTheCommandExactlyOneDelayLater) {
  PureDelayPlant plant({0.0173, 1e5, 8192.0, {}});
  plant.reset(0.002);
  const double dt = 1.0 / 1024.0, omega = 2.0 * std::numbers::pi * 1.3;
  double command = 0.002;
  for (int i = 1; i <= 2048; ++i) {
    const double t = i * dt;
    const double next = 0.002 + 0.01 * std::sin(omega * t);
    plant.advance(command, next, dt);
    command = next;
    const double delayed_time = t - 0.0173;
    // Before the delay has elapsed the specimen sits where it was reset.
    double expected = 0.002;
    if (delayed_time > 0.0) {
      // The command ramps linearly between samples, so the delayed value interpolates them.
      const double k = std::floor(delayed_time / dt);
      const double a = 0.002 + 0.01 * std::sin(omega * k * dt), b = 0.002 + 0.01 * std::sin(omega * (k + 1) * dt);
      expected = a + (b - a) * (delayed_time / dt - k);
    }
    ASSERT_NEAR(plant.measure().displacement_m, expected, 1e-12) << t;
    ASSERT_NEAR(plant.measure().force_n, 1e5 * expected, 1e-6);
  }
}

TEST(PureDelayPlant, AnIntervalOfTooManyPointsIsRefused) {
  PureDelayPlant plant({0.005, 0.0, 8192.0, {}});
  EXPECT_THROW(plant.advance(0.0, 0.0, 1e300), std::invalid_argument);
  EXPECT_NO_THROW(plant.advance(0.0, 0.0, 1.0 / 1024.0));
}

TEST(PureDelayPlant, FrequencyResponseIsUnitGainAndLinearPhase) {
  PureDelayPlant plant({0.025, 0.0, 8192.0, {}});
  for (double f : {0.5, 2.0, 7.0}) {
    const auto g = simulated_frequency_response(plant, SineTest{1e-3, f, 4096.0, 0.5, 4});
    EXPECT_NEAR(std::abs(g), 1.0, 1e-4) << f;
    EXPECT_NEAR(std::arg(g), -2.0 * std::numbers::pi * f * 0.025, 1e-4) << f;
  }
}

TEST(PureDelayPlant, StepArrivesAfterTheDelay) {
  PureDelayPlant plant({0.010, 0.0, 8192.0, {}});
  const double dt = 1.0 / 8192.0;
  plant.advance(0.0, 0.0, 0.005);
  plant.advance(0.001, 0.001, 0.0099);  // a jump to 1 mm at t = 5 ms
  EXPECT_DOUBLE_EQ(plant.measure().displacement_m, 0.0);
  plant.advance(0.001, 0.001, 2 * dt);
  EXPECT_DOUBLE_EQ(plant.measure().displacement_m, 0.001);
}

TEST(TransferFunctionPlant, FirstOrderStepResponseIsExponential) {
  const double tau = 0.05;
  TransferFunctionPlant plant({{Polynomial{1.0}, Polynomial{1.0, tau}}, 0.0, 8192.0, {}});
  const double dt = 1.0 / 1024.0;
  for (int i = 1; i <= 256; ++i) {
    plant.advance(i == 1 ? 0.0 : 0.01, 0.01, dt);
    // The first interval ramps from 0 to 10 mm; afterwards the command holds.
    const double t = i * dt;
    const double ramp_response = 0.01 / dt * (dt - tau * (1.0 - std::exp(-dt / tau)));  // at t = dt
    const double expected = 0.01 + (ramp_response - 0.01) * std::exp(-(t - dt) / tau);
    ASSERT_NEAR(plant.measure().displacement_m, expected, 1e-9) << t;
  }
}

// RTHS benchmark (Silva et al. 2020), closed loop without a specimen-side force: the
// sheet's transfer function and its published frequency response table.
TransferFunction benchmark_plant() {
  return {Polynomial{2.18385e13}, Polynomial{2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13}};
}

TEST(TransferFunctionPlant, MatchesTheRthsBenchmarkFrequencyResponseTable) {
  TransferFunctionPlant plant({benchmark_plant(), 0.0, 8192.0, {}});
  struct Row {
    double f, gain, delay_ms;
  };
  for (const Row& row : {Row{1.0, 0.9994, 24.96}, Row{5.0, 0.8509, 22.74}, Row{10.0, 0.6329, 19.01}}) {
    const auto g = simulated_frequency_response(plant, SineTest{1e-3, row.f, 4096.0, 1.0, 5});
    EXPECT_NEAR(std::abs(g), row.gain, 5e-4) << row.f;
    EXPECT_NEAR(-std::arg(g) / (2.0 * std::numbers::pi * row.f) * 1e3, row.delay_ms, 0.05) << row.f;
  }
}

TEST(TransferFunctionPlant, ResetHoldsTheRequestedDisplacement) {
  TransferFunctionPlant plant({benchmark_plant(), 1.19e6, 8192.0, {}});
  plant.reset(0.003);
  const double command = 0.003 / benchmark_plant().static_gain();
  for (int i = 0; i < 512; ++i) plant.advance(command, command, 1.0 / 4096.0);
  EXPECT_NEAR(plant.measure().displacement_m, 0.003, 1e-12);
  EXPECT_NEAR(plant.measure().force_n, 1.19e6 * 0.003, 1e-6);
}

TEST(TransferFunctionPlant, RejectsUnstableAndImproperModels) {
  EXPECT_THROW(TransferFunctionPlant({{Polynomial{1.0}, Polynomial{-1.0, 1.0}}, 0.0, 8192.0, {}}),
               std::invalid_argument);
  EXPECT_THROW(TransferFunctionPlant({{Polynomial{0.0, 0.0, 1.0}, Polynomial{1.0, 1.0}}, 0.0, 8192.0, {}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::servo
