// What holds for every kind and geometry: forces through the transposed Jacobian obey virtual
// work against finite differences of the strokes, displacement -> strokes -> displacement
// round trips, the actuator forces that carry DOF forces; and what PlanarSetup refuses or
// reports: a singular geometry at construction, a singular configuration, strokes no
// configuration reaches.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/LU>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/setups/planar_setup.h"
#include "setup_examples.h"

namespace rpsd::setups {
namespace {

std::vector<std::pair<std::string, PlanarGeometry>> every_example() {
  std::vector<std::pair<std::string, PlanarGeometry>> all;
  for (const Geometry g : {Geometry::kLinear, Geometry::kLargeDisplacement}) {
    const std::string suffix = g == Geometry::kLinear ? " linear" : " large";
    all.emplace_back("one_actuator x" + suffix, examples::one_actuator(g).planar());
    all.emplace_back("one_actuator y" + suffix, examples::one_actuator(g, DofMotion::kTranslationY).planar());
    for (const ActuatorSide side : {ActuatorSide::kLeft, ActuatorSide::kRight}) {
      const std::string at = side == ActuatorSide::kLeft ? " left" : " right";
      all.emplace_back("two_actuators" + at + suffix, examples::two_actuators(g, side).planar());
      all.emplace_back("three_actuators" + at + suffix, examples::three_actuators(g, side).planar());
      all.emplace_back("three_actuators no offsets" + at + suffix, examples::three_actuators(g, side, false).planar());
    }
    all.emplace_back("planar" + suffix, examples::planar(g).planar());
  }
  return all;
}

// Configurations up to 0.3 rad and 0.12 m, cut to the setup's DOFs.
std::vector<SetupVector> configurations(const PlanarSetup& s) {
  const std::vector<std::array<double, 3>> all = {
      {0.0, 0.0, 0.0}, {0.01, -0.004, 0.002}, {0.05, 0.02, -0.1}, {-0.08, 0.03, 0.2}, {0.12, -0.05, 0.3}};
  std::vector<SetupVector> out;
  for (const auto& c : all) {
    SetupVector u(s.dofs());
    for (int j = 0; j < s.dofs(); ++j) {
      const DofMotion m = s.geometry().dofs[static_cast<std::size_t>(j)];
      u[j] = m == DofMotion::kTranslationX ? c[0] : m == DofMotion::kTranslationY ? c[1] : c[2];
    }
    out.push_back(u);
  }
  return out;
}

// F_dof · δu = Σ f_act · δs: each DOF force is Σ_i f_i ∂s_i/∂u_j, the derivative taken by
// central differences of strokes(), so a force transformation that is not Jᵀ of the very
// strokes the setup commands fails.
TEST(PlanarSetup, ForcesObeyVirtualWork) {
  for (const auto& [name, geometry] : every_example()) {
    const PlanarSetup s(geometry);
    const int n = s.dofs();
    SetupVector f(n);
    for (int i = 0; i < n; ++i) f[i] = 1000.0 * (i + 1) * (i % 2 == 0 ? 1.0 : -1.3);
    for (const SetupVector& u : configurations(s)) {
      SetupVector forces;
      s.dof_forces(u, f, forces);
      for (int j = 0; j < n; ++j) {
        const double h = 1e-6;
        SetupVector plus = u, minus = u, s_plus, s_minus;
        plus[j] += h;
        minus[j] -= h;
        s.strokes(plus, s_plus);
        s.strokes(minus, s_minus);
        const double work_per_unit = f.dot(s_plus - s_minus) / (2 * h);
        EXPECT_NEAR(forces[j], work_per_unit, 1e-5 * f.cwiseAbs().maxCoeff()) << name << " DOF " << j;
      }
    }
  }
}

TEST(PlanarSetup, DisplacementStrokesDisplacementRoundTrips) {
  for (const auto& [name, geometry] : every_example()) {
    const PlanarSetup s(geometry);
    SetupVector previous = SetupVector::Zero(s.dofs());
    for (const SetupVector& u : configurations(s)) {
      SetupVector strokes, back;
      s.strokes(u, strokes);
      ASSERT_EQ(s.displacements(strokes, previous, back), SetupStatus::kOk) << name;
      for (int j = 0; j < s.dofs(); ++j) EXPECT_NEAR(back[j], u[j], 1e-12) << name << " DOF " << j;
      previous = back;
    }
  }
}

// What a simulated specimen loads each actuator with: Jᵀ f = F solved, so that the DOF forces
// come back.
TEST(PlanarSetup, ActuatorForcesCarryTheDofForces) {
  for (const auto& [name, geometry] : every_example()) {
    const PlanarSetup s(geometry);
    SetupVector wanted(s.dofs());
    for (int j = 0; j < s.dofs(); ++j) wanted[j] = 2500.0 * (j + 1) - 4000.0;
    for (const SetupVector& u : configurations(s)) {
      SetupVector f, back;
      ASSERT_EQ(s.actuator_forces(u, wanted, f), SetupStatus::kOk) << name;
      s.dof_forces(u, f, back);
      for (int j = 0; j < s.dofs(); ++j) EXPECT_NEAR(back[j], wanted[j], 1e-8) << name << " DOF " << j;
    }
  }
}

// Linear geometry: one Jacobian everywhere, the one at the reference configuration.
TEST(PlanarSetup, LinearGeometryUsesTheReferenceJacobianEverywhere) {
  const PlanarSetup s(examples::planar(Geometry::kLinear).planar());
  SetupMatrix at_rest, far;
  s.jacobian(SetupVector::Zero(3), at_rest);
  s.jacobian(configurations(s).back(), far);
  EXPECT_EQ(at_rest, far);
  const PlanarSetup large(examples::planar(Geometry::kLargeDisplacement).planar());
  SetupMatrix large_far;
  large.jacobian(configurations(s).back(), large_far);
  EXPECT_GT((large_far - far).cwiseAbs().maxCoeff(), 0.01);
}

std::string refusal(const PlanarGeometry& g) {
  try {
    const PlanarSetup s(g);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(PlanarSetup, RefusesGeometriesThatCannotHoldTheirDofs) {
  PlanarGeometry no_lever = examples::two_actuators(Geometry::kLinear).planar();
  no_lever.actuators[1].attachment_m = {0.0, 0.0};  // both at the control point: no lever arm
  no_lever.actuators[1].fixed_end_m = {-1.5, 0.0};
  EXPECT_NE(refusal(no_lever).find("singular"), std::string::npos) << refusal(no_lever);

  PlanarGeometry parallel = examples::three_actuators(Geometry::kLargeDisplacement).planar();
  parallel.actuators[0].fixed_end_m = parallel.actuators[0].attachment_m + Eigen::Vector2d(0.0, -1.0);  // vertical
  EXPECT_NE(refusal(parallel).find("singular"), std::string::npos) << refusal(parallel);

  PlanarGeometry zero = examples::planar(Geometry::kLinear).planar();
  zero.actuators[2].fixed_end_m = zero.actuators[2].attachment_m;
  EXPECT_EQ(refusal(zero), "actuator 3 (south_west): its fixed end and its attachment point coincide (zero length)");

  PlanarGeometry twice = examples::planar(Geometry::kLinear).planar();
  twice.dofs[2] = DofMotion::kTranslationX;
  EXPECT_EQ(refusal(twice), "the setup's DOFs 1 and 3 are both translation_x");

  PlanarGeometry none;
  EXPECT_NE(refusal(none).find("1 to 3 DOFs"), std::string::npos);
}

// two_actuators with La2 = L: at θ = π/4 actuator 2's line passes through the control point, so
// it has no lever arm about it and the Jacobian is singular. Newton from there, and the forces
// there, say so instead of dividing by zero.
TEST(PlanarSetup, ReportsASingularConfiguration) {
  TwoActuatorsParameters p = examples::two_actuators(Geometry::kLargeDisplacement);
  p.actuator_length_m[1] = p.distance_between_actuators_m;
  const PlanarSetup s(p.planar());
  SetupVector singular(2);
  singular << 0.0, std::numbers::pi / 4.0;
  SetupMatrix j;
  s.jacobian(singular, j);
  EXPECT_NEAR(j.determinant(), 0.0, 1e-12);

  SetupVector strokes(2), u, f;
  strokes << 0.01, 0.02;
  EXPECT_EQ(s.displacements(strokes, singular, u), SetupStatus::kSingular);
  EXPECT_EQ(s.actuator_forces(singular, strokes, f), SetupStatus::kSingular);
  EXPECT_EQ(s.displacements(strokes, SetupVector::Zero(2), u), SetupStatus::kOk);  // from elsewhere it solves
}

// A shortening longer than the actuator: no configuration has it. Newton wanders between
// configurations and gives up after its bounded iterations.
TEST(PlanarSetup, ReportsUnreachableStrokesAsNotConverged) {
  const PlanarSetup s(examples::one_actuator(Geometry::kLargeDisplacement).planar());
  SetupVector strokes(1), u;
  strokes << -2.0 * s.reference_length_m(0);
  EXPECT_EQ(s.displacements(strokes, SetupVector::Zero(1), u), SetupStatus::kNotConverged);

  // Two actuators whose strokes differ by more than the lever arm can turn.
  const PlanarSetup two(examples::two_actuators(Geometry::kLargeDisplacement).planar());
  SetupVector apart(2);
  apart << 0.0, 1.5;  // actuator 2 would need 3.0 m; its pin reaches at most 1.7 + 0.8 m away
  const SetupStatus status = two.displacements(apart, SetupVector::Zero(2), u);
  EXPECT_NE(status, SetupStatus::kOk) << setup_status_text(status);
}

// One actuator of length L pinned at x = -L: strokes s = |x + L| - L, so x and -2L - x give
// the same stroke, with dstroke/dx of opposite signs. Newton from a guess beyond the fixed end
// finds the mirrored x; that is refused, not taken for the specimen's displacement.
TEST(PlanarSetup, RefusesTheMirroredSolutionOfTheMeasuredStrokes) {
  const PlanarSetup s(examples::one_actuator(Geometry::kLargeDisplacement).planar());
  const double l = s.reference_length_m(0);
  SetupVector strokes(1), u;
  strokes << 0.01;
  ASSERT_EQ(s.displacements(strokes, SetupVector::Constant(1, 0.0), u), SetupStatus::kOk);
  EXPECT_NEAR(u[0], 0.01, 1e-12);
  EXPECT_EQ(s.displacements(strokes, SetupVector::Constant(1, -2.0 * l - 0.005), u), SetupStatus::kMirrored);
  EXPECT_NEAR(u[0], -2.0 * l - 0.01, 1e-9);  // the mirror image it found
  EXPECT_NE(setup_status_text(SetupStatus::kMirrored).find("mirrored"), std::string_view::npos);
}

// The first call has no last solution: a guess of another size starts from the linear one
// (on d82d167 Newton read past the empty guess).
TEST(PlanarSetup, StartsFromTheLinearSolutionWithoutAGuess) {
  const PlanarSetup s(examples::three_actuators(Geometry::kLargeDisplacement).planar());
  SetupVector u(3), strokes, back;
  u << 0.05, -0.02, 0.15;
  s.strokes(u, strokes);
  ASSERT_EQ(s.displacements(strokes, SetupVector(), back), SetupStatus::kOk);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(back[j], u[j], 1e-12);
  // A last solution that was not finite (a failed step's) is no start either.
  const SetupVector lost = SetupVector::Constant(3, std::numeric_limits<double>::quiet_NaN());
  ASSERT_EQ(s.displacements(strokes, lost, back), SetupStatus::kOk);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(back[j], u[j], 1e-12);
}

}  // namespace
}  // namespace rpsd::setups
