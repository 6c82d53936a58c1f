// The plant's derivative is written for speed (parameters folded into products and
// reciprocals, one square root, a cheaper tanh). These tests hold it to the seed paper's
// Eqs. 1-4 written out plainly, and the tanh to std::tanh, within round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include "paper_rig.h"
#include "rpsd/servo/regularised_tanh.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/specimen_forces.h"

namespace rpsd::servo {
namespace {

std::int64_t ulps_apart(double a, double b) {
  std::int64_t ia = 0, ib = 0;
  std::memcpy(&ia, &a, sizeof a);
  std::memcpy(&ib, &b, sizeof b);
  return ia > ib ? ia - ib : ib - ia;  // same sign here: tanh keeps the sign of x
}

TEST(RegularisedTanh, WithinTwoUlpsOfStdTanhAndExactlyOneWhereTanhRoundsToOne) {
  std::int64_t worst = 0;
  for (double x = -25.0; x <= 25.0; x += 3.7e-5) {
    if (x == 0.0) continue;
    worst = std::max(worst, ulps_apart(regularised_tanh(x), std::tanh(x)));
  }
  for (double x = 1e-12; x < 0.6; x *= 1.00001) {  // the rational form near zero, finely
    worst = std::max(
        {worst, ulps_apart(regularised_tanh(x), std::tanh(x)), ulps_apart(regularised_tanh(-x), std::tanh(-x))});
  }
  EXPECT_LE(worst, 2);
  for (double x : {19.1, 19.2, 22.0, 100.0, 1e300}) {
    EXPECT_EQ(regularised_tanh(x), 1.0);
    EXPECT_EQ(regularised_tanh(-x), -1.0);
    EXPECT_EQ(std::tanh(x), 1.0);
  }
  EXPECT_EQ(regularised_tanh(0.0), 0.0);
  EXPECT_EQ(regularised_tanh(1e-300), std::tanh(1e-300));
}

// Eqs. 1-4 and the specimen, as the header states them, one operation at a time. `scale`
// receives, per rate, the sum of the magnitudes of its terms: round-off is relative to it.
ServoHydraulicPlant::State plain_derivative(const ServoSystemParameters& p, const ServoHydraulicPlant::State& s,
                                            double u, double udot, ServoHydraulicPlant::State& scale) {
  const double xv = s[0], q = s[1], pl = s[2], x = s[3], xdot = s[4];
  const auto& v = p.servovalve;
  const double c_f = p.sensors.lvdt_gain_v_per_m;
  const double gp = p.controller.proportional_gain * c_f, gd = p.controller.derivative_gain_s * c_f;
  const double command_v = gp * (u - x) + gd * (udot - xdot);
  const double feedback_v = v.spool_lvdt_gain_v_per_m * v.max_spool_stroke_m * xv;
  const double qdot = (v.pilot_flow_gain_m3_per_s_per_v * (command_v - feedback_v) - q) / v.pilot_time_constant_s;
  double xvdot = q / (v.max_spool_stroke_m * v.main_spool_area_m2);
  if ((xv >= 1.0 && xvdot > 0.0) || (xv <= -1.0 && xvdot < 0.0)) xvdot = 0.0;
  const double kv = p.flow.nonlinear_flow_gain ? p.flow.no_load_flow_gain_m3_per_s /
                                                     std::sqrt(1.0 + std::pow(p.flow.flow_gain_rolloff * xv, 2))
                                               : p.flow.no_load_flow_gain_m3_per_s;
  const double sign = xv > 0.0 ? 1.0 : -1.0;
  const double drop =
      p.flow.load_pressure_effect ? std::clamp(1.0 - sign * pl / p.flow.supply_pressure_pa, 0.0, 2.0) : 1.0;
  const double flow = kv * xv * std::sqrt(drop);
  const auto& a = p.actuator;
  const double ka = a.compressibility_m5_per_n();
  const double pdot = (flow - a.piston_area_m2 * xdot - a.leakage_m3_per_s_per_pa * pl) / ka;
  const double spring = p.specimen.stiffness.initial_n_per_m * x, damper = p.specimen.damping_n_s_per_m() * xdot;
  const double friction =
      p.specimen.friction_force_n * std::tanh(xdot / p.specimen.friction_regularisation_velocity_m_per_s);
  const double m = p.specimen.mass_kg;
  ServoHydraulicPlant::State r;
  r << xvdot, qdot, pdot, xdot, (a.piston_area_m2 * pl - spring - damper - friction) / m;
  scale << std::abs(xvdot),
      (v.pilot_flow_gain_m3_per_s_per_v *
           (std::abs(gp * (u - x)) + std::abs(gd * (udot - xdot)) + std::abs(feedback_v)) +
       std::abs(q)) /
          v.pilot_time_constant_s,
      (std::abs(flow) + std::abs(a.piston_area_m2 * xdot) + std::abs(a.leakage_m3_per_s_per_pa * pl)) / ka,
      std::abs(xdot), (std::abs(a.piston_area_m2 * pl) + std::abs(spring) + std::abs(damper) + std::abs(friction)) / m;
  return r;
}

TEST(ServoHydraulicPlant, DerivativeEqualsThePaperEquationsWrittenPlainlyWithinRoundOff) {
  ServoSystemParameters p = testing::paper_rig();
  ASSERT_TRUE(!p.specimen.stiffness.is_bilinear() || p.specimen.stiffness.change_displacement_m > 0.02);
  std::mt19937_64 random(20261121);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int variant = 0; variant < 4; ++variant) {
    p.flow.nonlinear_flow_gain = (variant & 1) != 0;
    p.flow.load_pressure_effect = (variant & 2) != 0;
    const ServoHydraulicPlant plant(p);
    for (int i = 0; i < 2000; ++i) {
      ServoHydraulicPlant::State s;
      // Openings beyond the stops, pressures up to 1.5 P_s, the spring's first branch, and
      // velocities through the friction's regularisation band.
      s << 1.1 * unit(random), 1e-4 * unit(random), 1.5 * p.flow.supply_pressure_pa * unit(random), 0.02 * unit(random),
          0.3 * std::pow(unit(random), 3);
      const double u = 0.02 * unit(random), udot = 0.2 * unit(random);
      ServoHydraulicPlant::State scale;
      const auto plain = plain_derivative(p, s, u, udot, scale);
      const auto fast = plant.derivative(s, u, udot);
      for (int k = 0; k < 5; ++k) {
        EXPECT_NEAR(fast[k], plain[k], 1e-13 * scale[k]) << "rate " << k << ", sample " << i << ", variant " << variant;
      }
    }
  }
}

}  // namespace
}  // namespace rpsd::servo
