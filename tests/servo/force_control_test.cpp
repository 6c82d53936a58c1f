// Force control of the seed paper's servo-hydraulic model (mixed control, issue 30), against
// the closed forms of its linearised force loop (docs/servo-model.md, "Force control"):
//   valve flow        Q = K_v0 K_s G_f (F_u - F) = g (F_u - F),   F = A P_L
//   chambers          K_a Pdot_L = Q - A xdot - C_l P_L
//   quasi-static      x = F / k (a spring specimen, its mass and damping left out)
// Steady state: g (F_u - F) = C_l F / A, so F = F_u g A / (g A + C_l) and x = F / k.
// Bandwidth: (K_a + A^2 / k) Fdot / A = g F_u - (g + C_l / A) F, a first-order lag of
// omega_F = (g A + C_l) / (K_a + A^2 / k) rad/s.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "paper_rig.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::servo {
namespace {

constexpr double kPeriodS = 1.0 / 1024.0;

// The paper's rig with a force gain: G_f = 1e-5 V/N is stable with its 7080 kg specimen (the
// loop's gain against the oil column, G_f K_s K_v0 A / K_a, is ~300 rad/s; 4e-5 V/N is not).
constexpr double kForceGainVPerN = 1e-5;

ServoSystemParameters force_rig() {
  ServoSystemParameters p = testing::paper_rig();
  p.controller.force_gain_v_per_n = kForceGainVPerN;
  return p;
}

// The paper's rig on a linear spring with the valve's flow linear (Eq. 7), so that the closed
// forms above are exact in steady state.
ServoSystemParameters linear_rig() {
  ServoSystemParameters p = force_rig();
  p.flow.nonlinear_flow_gain = false;
  p.flow.load_pressure_effect = false;
  p.specimen.stiffness.change_displacement_m = 0.0;
  return p;
}

// g = K_v0 K_s G_f: flow per newton of force error, m^3/(s N).
double flow_per_force_error(const ServoSystemParameters& p) {
  return p.flow.no_load_flow_gain_m3_per_s * p.servovalve.static_gain_per_v() * p.controller.force_gain_v_per_n;
}

struct ForceChannel {
  explicit ForceChannel(const ServoSystemParameters& p) : plant(p), actuator(plants) {}
  ServoHydraulicPlant plant;
  std::array<Plant*, 1> plants{&plant};
  SimulatedActuator actuator;
  ActuatorReading reading;

  ActuatorStatus step(ControlMode mode, double x_m, double force_n, double period_s = kPeriodS) {
    const double x[1] = {x_m}, f[1] = {force_n};
    const ControlMode m[1] = {mode};
    return actuator.exchange_mixed(x, f, m, period_s, reading);
  }
};

TEST(ForceControl, WithoutAStatedForceGainTheModelHasNoForceLoop) {
  const ServoSystemParameters p = testing::paper_rig();
  ASSERT_EQ(p.controller.force_gain_v_per_n, 0.0);
  ServoHydraulicPlant plant(p);
  std::array<Plant*, 1> plants{&plant};
  SimulatedActuator actuator(plants);
  EXPECT_FALSE(actuator.controls_force(0));
  EXPECT_TRUE(ForceChannel(force_rig()).actuator.controls_force(0));
}

TEST(ForceControl, HoldingAForceOnALinearSpringSettlesAtTheForceOverItsStiffness) {
  const ServoSystemParameters p = linear_rig();
  ForceChannel channel(p);
  const double x0[1] = {0.0};
  channel.actuator.start(x0);
  const double force_n = 10e3, k = p.specimen.stiffness.initial_n_per_m;
  const double gA = flow_per_force_error(p) * p.actuator.piston_area_m2, leak = p.actuator.leakage_m3_per_s_per_pa;
  const double settled_n = force_n * gA / (gA + leak);  // the loop's steady-state error is force_n - settled_n
  ASSERT_GT(force_n - settled_n, 50.0);                 // about 0.9 %: large enough to be seen
  for (int i = 0; i < 60 * 1024; ++i) ASSERT_EQ(channel.step(ControlMode::kForce, 0.0, force_n), ActuatorStatus::kOk);
  EXPECT_NEAR(channel.reading.force_n[0], settled_n, 1e-3 * (force_n - settled_n));
  EXPECT_NEAR(channel.reading.displacement_m[0], settled_n / k, 1e-9);
}

TEST(ForceControl, AForceStepRisesWithTheLoopsFirstOrderBandwidth) {
  // A light specimen without friction: the specimen's own mode (k/m) lies far above the loop's.
  ServoSystemParameters p = linear_rig();
  p.specimen.mass_kg = 10.0;
  p.specimen.friction_force_n = 0.0;
  ForceChannel channel(p);
  const double x0[1] = {0.0};
  channel.actuator.start(x0);
  const double k = p.specimen.stiffness.initial_n_per_m, A = p.actuator.piston_area_m2;
  const double gA = flow_per_force_error(p) * A, leak = p.actuator.leakage_m3_per_s_per_pa;
  const double omega = (gA + leak) / (p.actuator.compressibility_m5_per_n() + A * A / k);
  const double settled_n = 10e3 * gA / (gA + leak);
  // The command steps within the first period (a ramp over one period of 1 ms against a time
  // constant of ~0.7 s); compare at one and two time constants.
  double t = 0.0;
  for (double at : {1.0 / omega, 2.0 / omega}) {
    while (t + 0.5 * kPeriodS < at) {
      ASSERT_EQ(channel.step(ControlMode::kForce, 0.0, 10e3), ActuatorStatus::kOk);
      t += kPeriodS;
    }
    const double expected = settled_n * (1.0 - std::exp(-omega * (t - 0.5 * kPeriodS)));
    EXPECT_NEAR(channel.reading.force_n[0], expected, 0.02 * settled_n) << "at t = " << t << " s";
  }
}

TEST(ForceControl, EnteringForceControlStartsFromTheMeasuredForce) {
  const ServoSystemParameters p = force_rig();
  ForceChannel channel(p);
  const double x0[1] = {0.005};
  channel.actuator.start(x0);
  for (int i = 0; i < 1024; ++i) channel.step(ControlMode::kDisplacement, 0.005, 0.0);
  const double x_before = channel.reading.displacement_m[0], f_before = channel.reading.force_n[0];
  ASSERT_GT(f_before, 3000.0);
  // A force command equal to the measured force: the piston stays, but for the slow drift of
  // the loop's steady-state error (leakage, ~8 % at this gain: tens of micrometres here). The
  // periods are long (1/16 s), so that a ramp from any other force would show.
  for (int i = 0; i < 4; ++i) {
    ASSERT_EQ(channel.step(ControlMode::kForce, 0.0, f_before, 1.0 / 16.0), ActuatorStatus::kOk);
    EXPECT_NEAR(channel.reading.displacement_m[0], x_before, 1e-4) << "period " << i;
  }
}

TEST(ForceControl, LeavingForceControlStartsFromTheMeasuredDisplacement) {
  const ServoSystemParameters p = force_rig();
  ForceChannel channel(p);
  const double x0[1] = {0.0};
  channel.actuator.start(x0);
  for (int i = 0; i < 4 * 1024; ++i) channel.step(ControlMode::kForce, 0.0, 7e3);
  const double x_held = channel.reading.displacement_m[0];
  ASSERT_GT(x_held, 0.008);
  // Back in displacement control, holding the measured position: the piston stays there
  // (the previous displacement command, 0, is not where the ramp starts).
  for (int i = 0; i < 4; ++i) {
    ASSERT_EQ(channel.step(ControlMode::kDisplacement, x_held, 0.0, 1.0 / 16.0), ActuatorStatus::kOk);
    EXPECT_NEAR(channel.reading.displacement_m[0], x_held, 2e-4) << "period " << i;
  }
}

TEST(ForceControl, APlantWithoutAForceLoopIsRefused) {
  PureDelayPlant delay({0.0, 1e5, 8192.0, {}});
  std::array<Plant*, 1> plants{&delay};
  SimulatedActuator actuator(plants);
  EXPECT_FALSE(actuator.controls_force(0));
  const double x0[1] = {0.0};
  actuator.start(x0);
  const double x[1] = {0.0}, f[1] = {1e3};
  const ControlMode force[1] = {ControlMode::kForce}, displacement[1] = {ControlMode::kDisplacement};
  ActuatorReading reading;
  EXPECT_EQ(actuator.exchange_mixed(x, f, force, kPeriodS, reading), ActuatorStatus::kFault);
  EXPECT_EQ(actuator.exchange_mixed(x, f, displacement, kPeriodS, reading), ActuatorStatus::kOk);
}

TEST(ForceControl, AllChannelsInDisplacementControlGiveExactlyTheDisplacementPath) {
  const ServoSystemParameters p = testing::paper_rig();
  ForceChannel mixed(p), plain(p);
  const double x0[1] = {0.0};
  mixed.actuator.start(x0);
  plain.actuator.start(x0);
  for (int i = 0; i < 512; ++i) {
    const double x = 0.01 * std::sin(2.0 * 3.14159 * i * kPeriodS);
    const double command[1] = {x};
    mixed.step(ControlMode::kDisplacement, x, 123.0);
    plain.actuator.exchange(command, kPeriodS, plain.reading);
    ASSERT_EQ(mixed.reading.displacement_m[0], plain.reading.displacement_m[0]);
    ASSERT_EQ(mixed.reading.force_n[0], plain.reading.force_n[0]);
  }
}

}  // namespace
}  // namespace rpsd::servo
