// Each kind's strokes, inverse and forces against formulas derived by hand for its figure in
// docs/experimental-setups.md (written out here, not taken from the code), at small and large
// rotations, in linear and large-displacement geometry.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "rpsd/setups/planar_setup.h"
#include "setup_examples.h"

namespace rpsd::setups {
namespace {

constexpr Geometry kLinear = Geometry::kLinear;
constexpr Geometry kLarge = Geometry::kLargeDisplacement;

SetupVector vec(std::initializer_list<double> values) {
  SetupVector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double x : values) v[i++] = x;
  return v;
}

SetupVector strokes_of(const PlanarSetup& s, const SetupVector& u) {
  SetupVector out;
  s.strokes(u, out);
  return out;
}

SetupVector solve(const PlanarSetup& s, const SetupVector& strokes) {
  SetupVector u;
  EXPECT_EQ(s.displacements(strokes, SetupVector::Zero(s.dofs()), u), SetupStatus::kOk);
  return u;
}

SetupVector dof_forces_of(const PlanarSetup& s, const SetupVector& u, const SetupVector& f) {
  SetupVector out;
  s.dof_forces(u, f, out);
  return out;
}

void expect_near(const SetupVector& got, const SetupVector& want, double tolerance, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (Eigen::Index i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], tolerance) << what << " [" << i << "]";
}

// (x, θ): a small motion, and rotations of 0.1 to 0.3 rad where the geometries part.
const std::vector<std::array<double, 2>> kTwoDofConfigurations = {
    {0.01, 0.002}, {0.05, -0.1}, {-0.08, 0.2}, {0.12, 0.3}, {-0.03, -0.25}};
// (x, y, θ)
const std::vector<std::array<double, 3>> kThreeDofConfigurations = {
    {0.01, -0.004, 0.002}, {0.05, 0.02, -0.1}, {-0.08, 0.03, 0.2}, {0.12, -0.05, 0.3}, {-0.03, 0.06, -0.25}};

// one_actuator: the stroke is the displacement along its line, in either geometry (the other
// translation and the rotation are held).
TEST(OneActuatorSetup, StrokeIsTheDisplacementAlongItsLine) {
  for (const Geometry g : {kLinear, kLarge}) {
    for (const DofMotion m : {DofMotion::kTranslationX, DofMotion::kTranslationY}) {
      const PlanarSetup s(examples::one_actuator(g, m).planar());
      for (const double u : {-0.2, -0.01, 0.0, 0.03, 0.25}) {
        EXPECT_NEAR(strokes_of(s, vec({u}))[0], u, 1e-15);
        EXPECT_NEAR(solve(s, vec({u}))[0], u, 1e-15);
        EXPECT_NEAR(dof_forces_of(s, vec({u}), vec({1234.5}))[0], 1234.5, 1e-9);
      }
      EXPECT_DOUBLE_EQ(s.reference_length_m(0), 1.25);
    }
  }
}

// two_actuators, fixed ends on the left (OpenFresco's posAct left): actuator 1 at the control
// point, actuator 2 at L above it.
//   linear: s1 = x, s2 = x - L θ
//   large:  s1 = x, s2 = sqrt((x - L sin θ + La2)^2 + (L cos θ - L)^2) - La2
TEST(TwoActuatorsSetup, LeftStrokesAgainstClosedForms) {
  const double la2 = 1.5, l = 0.8;
  const PlanarSetup linear(examples::two_actuators(kLinear).planar());
  const PlanarSetup large(examples::two_actuators(kLarge).planar());
  for (const auto& [x, t] : kTwoDofConfigurations) {
    const SetupVector u = vec({x, t});
    expect_near(strokes_of(linear, u), vec({x, x - l * t}), 1e-15, "linear");
    const double s2 = std::hypot(x - l * std::sin(t) + la2, l * std::cos(t) - l) - la2;
    expect_near(strokes_of(large, u), vec({x, s2}), 1e-12, "large");
  }
}

// Fixed ends on the right: a positive stroke pushes toward -x.
//   linear: s1 = -x, s2 = -x + L θ
//   large:  s1 = -x, s2 = sqrt((x - L sin θ - La2)^2 + (L cos θ - L)^2) - La2
TEST(TwoActuatorsSetup, RightStrokesAgainstClosedForms) {
  const double la2 = 1.5, l = 0.8;
  const PlanarSetup linear(examples::two_actuators(kLinear, ActuatorSide::kRight).planar());
  const PlanarSetup large(examples::two_actuators(kLarge, ActuatorSide::kRight).planar());
  for (const auto& [x, t] : kTwoDofConfigurations) {
    const SetupVector u = vec({x, t});
    expect_near(strokes_of(linear, u), vec({-x, -x + l * t}), 1e-15, "linear");
    const double s2 = std::hypot(x - l * std::sin(t) - la2, l * std::cos(t) - l) - la2;
    expect_near(strokes_of(large, u), vec({-x, s2}), 1e-12, "large");
  }
}

// The inverse by hand. Linear: x = s1, θ = (s1 - s2) / L (left); x = -s1, θ = (s2 - s1) / L
// (right). Large, left: with A = x + La2, the circle of actuator 2's length gives
// A sin θ + L cos θ = (A^2 + 2 L^2 - (La2 + s2)^2) / (2 L) =: C, so
// θ = atan2(A, L) - acos(C / sqrt(A^2 + L^2)) on the branch through θ = 0. Right: with
// B = La2 - x, -B sin θ + L cos θ = (B^2 + 2 L^2 - (La2 + s2)^2) / (2 L) =: C and
// θ = acos(C / sqrt(B^2 + L^2)) - atan2(B, L).
TEST(TwoActuatorsSetup, InverseAgainstClosedForms) {
  const double la2 = 1.5, l = 0.8;
  const std::vector<std::array<double, 2>> strokes = {{0.01, 0.008}, {0.05, 0.13}, {-0.08, -0.24}, {0.12, -0.1}};
  for (const ActuatorSide side : {ActuatorSide::kLeft, ActuatorSide::kRight}) {
    const bool left = side == ActuatorSide::kLeft;
    const PlanarSetup linear(examples::two_actuators(kLinear, side).planar());
    const PlanarSetup large(examples::two_actuators(kLarge, side).planar());
    for (const auto& [s1, s2] : strokes) {
      const double x = left ? s1 : -s1;
      expect_near(solve(linear, vec({s1, s2})), vec({x, left ? (s1 - s2) / l : (s2 - s1) / l}), 1e-15, "linear");
      double theta = 0.0;
      if (left) {
        const double a = x + la2;
        const double c = (a * a + 2 * l * l - (la2 + s2) * (la2 + s2)) / (2 * l);
        theta = std::atan2(a, l) - std::acos(c / std::hypot(a, l));
      } else {
        const double b = la2 - x;
        const double c = (b * b + 2 * l * l - (la2 + s2) * (la2 + s2)) / (2 * l);
        theta = std::acos(c / std::hypot(b, l)) - std::atan2(b, l);
      }
      expect_near(solve(large, vec({s1, s2})), vec({x, theta}), 1e-12, "large");
    }
  }
}

// Forces, left. Linear: F_x = f1 + f2, M = -L f2 (OpenFresco's transfDaqForce). Large: with e
// the unit vector along actuator 2 at the displaced configuration and its pin moving along
// (-L cos θ, -L sin θ) per radian, F_x = f1 + f2 e_x, M = f2 (-L cos θ e_x - L sin θ e_y).
TEST(TwoActuatorsSetup, ForcesAgainstClosedForms) {
  const double la2 = 1.5, l = 0.8;
  const PlanarSetup linear(examples::two_actuators(kLinear).planar());
  const PlanarSetup large(examples::two_actuators(kLarge).planar());
  const SetupVector f = vec({12000.0, -7000.0});
  for (const auto& [x, t] : kTwoDofConfigurations) {
    const SetupVector u = vec({x, t});
    expect_near(dof_forces_of(linear, u, f), vec({f[0] + f[1], -l * f[1]}), 1e-9, "linear");
    const double ex = x - l * std::sin(t) + la2, ey = l * std::cos(t) - l, n = std::hypot(ex, ey);
    const double moment = f[1] * (-l * std::cos(t) * ex / n - l * std::sin(t) * ey / n);
    expect_near(dof_forces_of(large, u, f), vec({f[0] + f[1] * ex / n, moment}), 1e-8, "large");
  }
}

// At 0.1 to 0.3 rad the linear strokes are visibly wrong: actuator 2's linear stroke -L θ
// misses the arc's L (θ - sin θ) and the pin's drop L (1 - cos θ) across the actuator, over a
// millimetre at 0.2 rad here.
TEST(TwoActuatorsSetup, LinearGeometryDepartsAtLargeRotations) {
  const PlanarSetup linear(examples::two_actuators(kLinear).planar());
  const PlanarSetup large(examples::two_actuators(kLarge).planar());
  const double small = std::abs(strokes_of(linear, vec({0.0, 0.002}))[1] - strokes_of(large, vec({0.0, 0.002}))[1]);
  EXPECT_LT(small, 1e-6);  // second order: ~ L θ^3 / 6 + L^2 θ^2 / (2 La2)
  for (const double t : {0.1, 0.2, 0.3}) {
    const double departure = std::abs(strokes_of(linear, vec({0.0, t}))[1] - strokes_of(large, vec({0.0, t}))[1]);
    EXPECT_GT(departure, 1e-4 * (t / 0.1) * (t / 0.1)) << t;
  }
  const double at_02 = std::abs(strokes_of(linear, vec({0.0, 0.2}))[1] - strokes_of(large, vec({0.0, 0.2}))[1]);
  EXPECT_NEAR(at_02, 1.160e-3, 0.01e-3);  // the figure docs/experimental-setups.md gives
}

// three_actuators, horizontal actuator on the left, with joint offsets (OpenFresco's JntOff2d
// L1..L6 = 0.2, 0.6, 0.9, -, 0.15, 0.25; La1..La3 = 1.1, 1.3, 1.4):
//   s0 = sqrt((x + (L1 + L2)(1 - cos θ) + La1)^2 + (y - (L1 + L2) sin θ)^2) - La1
//   s1 = sqrt((x + L2 (1 - cos θ) + L5 sin θ)^2 + (y - L2 sin θ + L5 (1 - cos θ) + La2)^2) - La2
//   s2 = sqrt((x - L3 (1 - cos θ) + L6 sin θ)^2 + (y + L3 sin θ + L6 (1 - cos θ) + La3)^2) - La3
// and on the right s0 = sqrt((x - (L3 + L4)(1 - cos θ) - La1)^2 + (y + (L3 + L4) sin θ)^2) - La1.
// Linear: s0 = ±x, s1 = y - L2 θ, s2 = y + L3 θ (the offsets act only in large displacement).
TEST(ThreeActuatorsSetup, StrokesAgainstClosedForms) {
  const double la1 = 1.1, la2 = 1.3, la3 = 1.4;
  for (const bool offsets : {true, false}) {
    const double l1 = offsets ? 0.2 : 0.0, l2 = 0.6, l3 = 0.9, l4 = offsets ? 0.3 : 0.0, l5 = offsets ? 0.15 : 0.0,
                 l6 = offsets ? 0.25 : 0.0;
    for (const ActuatorSide side : {ActuatorSide::kLeft, ActuatorSide::kRight}) {
      const bool left = side == ActuatorSide::kLeft;
      const PlanarSetup linear(examples::three_actuators(kLinear, side, offsets).planar());
      const PlanarSetup large(examples::three_actuators(kLarge, side, offsets).planar());
      for (const auto& [x, y, t] : kThreeDofConfigurations) {
        const SetupVector u = vec({x, y, t});
        const double c = 1.0 - std::cos(t), s = std::sin(t);
        expect_near(strokes_of(linear, u), vec({left ? x : -x, y - l2 * t, y + l3 * t}), 1e-15, "linear");
        const double s0 = left ? std::hypot(x + (l1 + l2) * c + la1, y - (l1 + l2) * s) - la1
                               : std::hypot(x - (l3 + l4) * c - la1, y + (l3 + l4) * s) - la1;
        const double s1 = std::hypot(x + l2 * c + l5 * s, y - l2 * s + l5 * c + la2) - la2;
        const double s2 = std::hypot(x - l3 * c + l6 * s, y + l3 * s + l6 * c + la3) - la3;
        expect_near(strokes_of(large, u), vec({s0, s1, s2}), 1e-12, offsets ? "large, offsets" : "large");
      }
    }
  }
}

// Linear inverse by hand (OpenFresco's transfDaqDisp): x = ±s0, y = (L3 s1 + L2 s2) / (L2 + L3),
// θ = (s2 - s1) / (L2 + L3). Large: no closed form; the solution must give the measured strokes
// back through the hand formulas above (StrokesAgainstClosedForms) and stay near the linear one.
TEST(ThreeActuatorsSetup, InverseAgainstClosedForms) {
  const double l2 = 0.6, l3 = 0.9;
  const std::vector<std::array<double, 3>> strokes = {{0.01, -0.02, 0.015}, {0.08, 0.1, -0.12}, {-0.1, -0.2, 0.15}};
  for (const ActuatorSide side : {ActuatorSide::kLeft, ActuatorSide::kRight}) {
    const PlanarSetup linear(examples::three_actuators(kLinear, side).planar());
    const PlanarSetup large(examples::three_actuators(kLarge, side).planar());
    for (const auto& [s0, s1, s2] : strokes) {
      const SetupVector want =
          vec({side == ActuatorSide::kLeft ? s0 : -s0, (l3 * s1 + l2 * s2) / (l2 + l3), (s2 - s1) / (l2 + l3)});
      expect_near(solve(linear, vec({s0, s1, s2})), want, 1e-15, "linear");
      const SetupVector u = solve(large, vec({s0, s1, s2}));
      expect_near(strokes_of(large, u), vec({s0, s1, s2}), 1e-12, "large");
    }
  }
}

// Linear forces (OpenFresco's transfDaqForce): F_x = ±f0, F_y = f1 + f2, M = -L2 f1 + L3 f2.
TEST(ThreeActuatorsSetup, LinearForcesAgainstClosedForms) {
  const double l2 = 0.6, l3 = 0.9;
  const SetupVector f = vec({5000.0, -3000.0, 8000.0});
  for (const ActuatorSide side : {ActuatorSide::kLeft, ActuatorSide::kRight}) {
    const PlanarSetup linear(examples::three_actuators(kLinear, side).planar());
    const double fx = side == ActuatorSide::kLeft ? f[0] : -f[0];
    expect_near(dof_forces_of(linear, vec({0.1, 0.05, 0.3}), f), vec({fx, f[1] + f[2], -l2 * f[1] + l3 * f[2]}), 1e-9,
                "linear");
  }
}

// The joint offsets matter in large displacement: at 0.2 rad the left actuator's stroke grows
// by about L5 (1 - cos θ) + (L5 sin θ)(L5 sin θ + 2 L2 (1 - cos θ)) / (2 La2) = 3.7 mm when its
// pin is 0.15 m below the link; not at all in linear geometry.
TEST(ThreeActuatorsSetup, JointOffsetsActInLargeDisplacement) {
  const SetupVector u = vec({0.0, 0.0, 0.2});
  const PlanarSetup with(examples::three_actuators(kLarge, ActuatorSide::kLeft, true).planar());
  const PlanarSetup without(examples::three_actuators(kLarge, ActuatorSide::kLeft, false).planar());
  EXPECT_NEAR(strokes_of(with, u)[1] - strokes_of(without, u)[1], 3.7e-3, 0.1e-3);
  const PlanarSetup linear_with(examples::three_actuators(kLinear, ActuatorSide::kLeft, true).planar());
  const PlanarSetup linear_without(examples::three_actuators(kLinear, ActuatorSide::kLeft, false).planar());
  EXPECT_NEAR(strokes_of(linear_with, u)[1], strokes_of(linear_without, u)[1], 1e-15);
}

}  // namespace
}  // namespace rpsd::setups
