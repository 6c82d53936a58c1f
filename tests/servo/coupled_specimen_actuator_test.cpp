// The coupled specimen on simulated actuators: the load cells against J^-T (K u + C du/dt)
// hand-computed for a two-actuator column top (translation and rotation), the actuators
// pushing against each other, the servo-hydraulic model's equilibrium under the coupled load,
// the external load in the model's specimen equation, and a geometry that fails faulting.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "paper_rig.h"
#include "rpsd/servo/coupled_specimen_actuator.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"

namespace rpsd::servo {
namespace {

constexpr double kDt = 1.0 / 1024.0;
constexpr double kLever_m = 0.8;  // actuator 2 above actuator 1
constexpr double kLength_m = 2.0;

// Two horizontal actuators from a reaction wall on the left: actuator 1 at the control point,
// actuator 2 kLever_m above it. DOFs x and θ. Linear: s1 = x, s2 = x - h θ.
setups::PlanarSetup column_top(setups::Geometry geometry = setups::Geometry::kLinear) {
  setups::PlanarGeometry g;
  g.geometry = geometry;
  g.dof_count = 2;
  g.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation, setups::DofMotion::kTranslationY};
  g.actuators[0] = {"bottom", {-kLength_m, 0.0}, {0.0, 0.0}};
  g.actuators[1] = {"top", {-kLength_m, kLever_m}, {0.0, kLever_m}};
  return setups::PlanarSetup(g);
}

// A cantilever column's top, EI = 1e6 N m^2 over 2 m: 12EI/L^3, -6EI/L^2, 4EI/L.
Eigen::MatrixXd column_stiffness() {
  Eigen::MatrixXd k(2, 2);
  k << 1.5e6, -1.5e6, -1.5e6, 2.0e6;
  return k;
}

// Jᵀ f = F with J = [[1, 0], [1, -h]]: f2 = -F_θ / h, f1 = F_x - f2.
std::array<double, 2> hand_loads(double force_x, double moment) {
  const double f2 = -moment / kLever_m;
  return {force_x - f2, f2};
}

// The servo-hydraulic loop's static error holding a load (integral gain zero): the spool at
// rest opens -K_s G_p C_F e, just enough that the valve replaces the leakage C_l P_L of the
// chambers carrying the load, P_L = load / A. By fixed point on e (the flow gain and the
// pressure drop frozen at each pass).
double static_error_m(const ServoSystemParameters& p, double load_n) {
  const double pressure = load_n / p.actuator.piston_area_m2;
  const double gain = p.controller.proportional_gain * p.sensors.lvdt_gain_v_per_m * p.servovalve.static_gain_per_v();
  double e = 0.0;
  for (int i = 0; i < 50; ++i) {
    const double opening = -gain * e;
    const double drop = std::sqrt(1.0 - std::copysign(1.0, opening) * pressure / p.flow.supply_pressure_pa);
    e = -p.actuator.leakage_m3_per_s_per_pa * pressure / (p.flow.flow_gain_at(opening) * drop) / gain;
  }
  return e;
}

struct PerfectRig {
  std::vector<std::unique_ptr<Plant>> owned;
  std::vector<Plant*> plants;
  explicit PerfectRig(const PlantConfig& config, int n = 2) {
    for (int i = 0; i < n; ++i) {
      owned.push_back(make_plant(coupled_plant_config(config)));
      plants.push_back(owned.back().get());
    }
  }
};

TEST(CoupledSpecimenActuator, LoadCellsReadTheInverseTransposedJacobianOfTheStiffness) {
  PerfectRig rig(PureDelayParameters{0.0, 4e5, 8192.0, {}, {}});  // its own k must not count
  CoupledSpecimenActuator actuator(rig.plants, column_top(), column_stiffness(), Eigen::MatrixXd());
  actuator.start(std::vector<double>{0.0, 0.0});
  const double x = 0.004, theta = 0.0025;
  const std::vector<double> strokes = {x, x - kLever_m * theta};
  ActuatorReading reading;
  for (int n = 0; n < 3; ++n) ASSERT_EQ(actuator.exchange(strokes, kDt, reading), ActuatorStatus::kOk);
  const auto f = hand_loads(1.5e6 * x - 1.5e6 * theta, -1.5e6 * x + 2.0e6 * theta);
  EXPECT_NEAR(reading.force_n[0], f[0], 1e-9 * std::abs(f[0]));
  EXPECT_NEAR(reading.force_n[1], f[1], 1e-9 * std::abs(f[1]));
  EXPECT_NEAR(actuator.dof_displacements()[0], x, 1e-15);
  EXPECT_NEAR(actuator.dof_displacements()[1], theta, 1e-15);
}

TEST(CoupledSpecimenActuator, ActuatorsPushAgainstEachOtherUnderTheCoupledStiffness) {
  PerfectRig rig(PureDelayParameters{});
  CoupledSpecimenActuator actuator(rig.plants, column_top(), column_stiffness(), Eigen::MatrixXd());
  actuator.start(std::vector<double>{0.0, 0.0});
  ActuatorReading reading;
  // A rotation alone: a couple (f1 = θ (k_xθ + k_θθ / h) = +2 kN, f2 = -k_θθ θ / h = -5 kN).
  const double theta = 0.002;
  ASSERT_EQ(actuator.exchange(std::vector<double>{0.0, -kLever_m * theta}, kDt, reading), ActuatorStatus::kOk);
  EXPECT_GT(reading.force_n[0], 0.0);
  EXPECT_LT(reading.force_n[1], 0.0);
  EXPECT_NEAR(reading.force_n[0], 2000.0, 1e-6);
  EXPECT_NEAR(reading.force_n[1], -5000.0, 1e-6);
  // A translation alone, which an uncoupled specimen would carry on actuator 1 only: the
  // off-diagonal stiffness makes the top actuator push (+18.75 kN) and the bottom one pull.
  const double x = 0.01;
  ASSERT_EQ(actuator.exchange(std::vector<double>{x, x}, kDt, reading), ActuatorStatus::kOk);
  EXPECT_LT(reading.force_n[0], 0.0);
  EXPECT_GT(reading.force_n[1], 0.0);
  EXPECT_NEAR(reading.force_n[0], -3750.0, 1e-6);
  EXPECT_NEAR(reading.force_n[1], 18750.0, 1e-6);
}

TEST(CoupledSpecimenActuator, DampingLoadsTheActuatorsWithTheDofVelocities) {
  PerfectRig rig(PureDelayParameters{});
  Eigen::MatrixXd c(2, 2);
  c << 3e4, -1e4, -1e4, 2e4;
  CoupledSpecimenActuator actuator(rig.plants, column_top(), column_stiffness(), c);
  actuator.start(std::vector<double>{0.0, 0.0});
  const double velocity_x = 0.05, rate_theta = 0.02;  // m/s, rad/s, held
  ActuatorReading reading;
  for (int n = 1; n <= 10; ++n) {
    const double x = velocity_x * n * kDt, theta = rate_theta * n * kDt;
    ASSERT_EQ(actuator.exchange(std::vector<double>{x, x - kLever_m * theta}, kDt, reading), ActuatorStatus::kOk);
    const Eigen::Vector2d force =
        column_stiffness() * Eigen::Vector2d(x, theta) + c * Eigen::Vector2d(velocity_x, rate_theta);
    const auto f = hand_loads(force[0], force[1]);
    EXPECT_NEAR(reading.force_n[0], f[0], 1e-6) << "period " << n;
    EXPECT_NEAR(reading.force_n[1], f[1], 1e-6) << "period " << n;
  }
}

TEST(CoupledSpecimenActuator, LargeDisplacementLoadsCarryTheDofForcesByVirtualWork) {
  PerfectRig rig(PureDelayParameters{});
  const setups::PlanarSetup setup = column_top(setups::Geometry::kLargeDisplacement);
  CoupledSpecimenActuator actuator(rig.plants, setup, column_stiffness(), Eigen::MatrixXd());
  setups::SetupVector u(2), strokes(2), dof_forces(2);
  u << 0.05, 0.15;  // a rotation where linear geometry is visibly off
  setup.strokes(u, strokes);
  actuator.start(std::vector<double>{strokes[0], strokes[1]});
  ActuatorReading reading;
  ASSERT_EQ(actuator.exchange(std::vector<double>{strokes[0], strokes[1]}, kDt, reading), ActuatorStatus::kOk);
  setups::SetupVector f(2);
  f << reading.force_n[0], reading.force_n[1];
  setup.dof_forces(u, f, dof_forces);
  const Eigen::Vector2d expected = column_stiffness() * Eigen::Vector2d(u[0], u[1]);
  EXPECT_NEAR(dof_forces[0], expected[0], 1e-6 * expected.norm());
  EXPECT_NEAR(dof_forces[1], expected[1], 1e-6 * expected.norm());
}

TEST(CoupledSpecimenActuator, InitialForcesAreTheLoadsAtRest) {
  PerfectRig rig(PureDelayParameters{});
  CoupledSpecimenActuator actuator(rig.plants, column_top(), column_stiffness(), Eigen::MatrixXd());
  const double x = 0.002;
  actuator.start(std::vector<double>{x, x});
  const auto f = hand_loads(1.5e6 * x, -1.5e6 * x);
  EXPECT_NEAR(rig.plants[0]->measure().force_n, f[0], 1e-6);
  EXPECT_NEAR(rig.plants[1]->measure().force_n, f[1], 1e-6);
}

// The servo-hydraulic model's steady state under a held command: the chambers carry exactly
// the coupled specimen's loads at the measured configuration, and the configuration is the
// commanded one to the loop's static error.
TEST(CoupledSpecimenActuator, ServoHydraulicPlantsSettleOnTheCoupledStiffness) {
  PerfectRig rig(rpsd::testing::paper_rig());
  Eigen::MatrixXd c(2, 2);
  c << 2e4, 0.0, 0.0, 1e4;
  CoupledSpecimenActuator actuator(rig.plants, column_top(), column_stiffness(), c);
  actuator.start(std::vector<double>{0.0, 0.0});
  const double x = 0.008, theta = 0.001;  // loads -2 kN and +12.5 kN
  const std::vector<double> target = {x, x - kLever_m * theta};
  ActuatorReading reading;
  for (int n = 1; n <= 4096; ++n) {  // a 0.5 s ramp, then held
    const double share = std::min(1.0, n / 512.0);
    ASSERT_EQ(actuator.exchange(std::vector<double>{share * target[0], share * target[1]}, kDt, reading),
              ActuatorStatus::kOk)
        << "period " << n;
  }
  const setups::SetupVector& u = actuator.dof_displacements();
  for (int i = 0; i < 2; ++i) {  // each stroke off its command by the loop's static error
    const double error = static_error_m(rpsd::testing::paper_rig(), reading.force_n[i]);
    EXPECT_GT(std::abs(error), 1e-5);
    EXPECT_NEAR(reading.displacement_m[i] - target[i], error, 0.02 * std::abs(error)) << "actuator " << i + 1;
  }
  const Eigen::Vector2d force = column_stiffness() * Eigen::Vector2d(u[0], u[1]);
  const auto f = hand_loads(force[0], force[1]);
  EXPECT_NEAR(reading.force_n[0], f[0], 1e-3 * std::abs(f[0]));
  EXPECT_NEAR(reading.force_n[1], f[1], 1e-3 * std::abs(f[1]));
  EXPECT_LT(reading.force_n[0] * reading.force_n[1], 0.0);  // they push against each other
}

// m x'' = A P_L - ... - f_ext: the load changes the acceleration by -f_ext / m and nothing else.
TEST(ServoHydraulicPlantExternalLoad, EntersTheSpecimenEquationAsAnOpposingForce) {
  const ServoSystemParameters p = rpsd::testing::paper_rig();
  ServoHydraulicPlant plant(p);
  ServoHydraulicPlant::State state;
  state << 0.1, 1e-6, 2e5, 0.003, 0.01;
  const ServoHydraulicPlant::State free = plant.derivative(state, 0.004, 0.02);
  plant.set_external_load_n(5000.0);
  const ServoHydraulicPlant::State loaded = plant.derivative(state, 0.004, 0.02);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(loaded[i], free[i]) << "state " << i;
  EXPECT_NEAR(loaded[4] - free[4], -5000.0 / p.specimen.mass_kg, 1e-12);
}

// A step load on the servo-controlled piston held at 0: it yields until the valve replaces the
// leakage the load's pressure drives, the loop's static compliance from the model's own
// equations (spool at rest: opening = -K_s G_p C_F x; chambers: Q_L(opening, P_L) = C_l P_L;
// piston: A P_L = k x + f).
TEST(ServoHydraulicPlantExternalLoad, AStepLoadMovesThePistonToTheModelsStaticEquilibrium) {
  const ServoSystemParameters p = rpsd::testing::paper_rig();
  ServoHydraulicPlant plant(p);
  plant.reset(0.0);
  const double load_n = 20e3;
  plant.set_external_load_n(load_n);
  for (int n = 0; n < 8192; ++n) plant.advance(0.0, 0.0, kDt);  // 8 s
  // The equilibrium, by fixed point on x: the error holding the spring's and the load's force.
  const double k = p.specimen.stiffness.initial_n_per_m;
  double x = 0.0;
  for (int i = 0; i < 50; ++i) x = static_error_m(p, k * x + load_n);
  ASSERT_LT(x, -1e-6);  // a load against positive strokes pushes the piston back
  EXPECT_NEAR(plant.measure().displacement_m, x, 0.01 * std::abs(x));
  EXPECT_NEAR(plant.measure().force_n, k * plant.measure().displacement_m + load_n, 1e-3 * load_n);
}

TEST(CoupledSpecimenActuator, AGeometryThatCannotBeSolvedFaultsTheActuator) {
  PerfectRig rig(PureDelayParameters{});
  CoupledSpecimenActuator actuator(rig.plants, column_top(setups::Geometry::kLargeDisplacement), column_stiffness(),
                                   Eigen::MatrixXd());
  actuator.start(std::vector<double>{0.0, 0.0});
  ActuatorReading reading;
  reading.force_n.fill(123.0);
  // The top actuator shorter than nothing: no configuration has these strokes.
  EXPECT_EQ(actuator.exchange(std::vector<double>{0.0, -3.0 * kLength_m}, kDt, reading), ActuatorStatus::kFault);
  EXPECT_NE(actuator.fault_text().find("coupled specimen"), std::string_view::npos) << actuator.fault_text();
  EXPECT_TRUE(std::isfinite(reading.force_n[0]) && std::isfinite(reading.force_n[1]));
  // Latched: a good command does not bring it back before a new start.
  EXPECT_EQ(actuator.exchange(std::vector<double>{0.0, 0.0}, kDt, reading), ActuatorStatus::kFault);
  actuator.start(std::vector<double>{0.0, 0.0});
  EXPECT_EQ(actuator.exchange(std::vector<double>{0.0, 0.0}, kDt, reading), ActuatorStatus::kOk);
  EXPECT_TRUE(actuator.fault_text().empty());
}

TEST(CoupledSpecimenActuator, RefusesAPlantThatCannotCarryALoadAndAMatrixOfTheWrongSize) {
  FeedbackControlledPlantParameters feedback;
  feedback.plant.transfer_function = {Polynomial{100.0}, Polynomial{100.0, 1.0}};
  EXPECT_THROW(coupled_plant_config(feedback), std::invalid_argument);
  auto loop = make_plant(feedback);
  PerfectRig rig(PureDelayParameters{}, 1);
  std::vector<Plant*> mixed = {rig.plants[0], loop.get()};
  EXPECT_THROW(CoupledSpecimenActuator(mixed, column_top(), column_stiffness(), Eigen::MatrixXd()),
               std::invalid_argument);
  PerfectRig two(PureDelayParameters{});
  EXPECT_THROW(CoupledSpecimenActuator(two.plants, column_top(), Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd()),
               std::invalid_argument);
}

TEST(CoupledPlantConfig, ZeroesThePlantsOwnSpecimenAndKeepsItsMass) {
  const auto servo = std::get<ServoSystemParameters>(coupled_plant_config(rpsd::testing::paper_rig()));
  EXPECT_EQ(servo.specimen.stiffness.initial_n_per_m, 0.0);
  EXPECT_EQ(servo.specimen.stiffness.secondary_n_per_m, 0.0);
  EXPECT_EQ(servo.specimen.damping_n_s_per_m(), 0.0);
  EXPECT_EQ(servo.specimen.mass_kg, rpsd::testing::paper_rig().specimen.mass_kg);
  TransferFunctionPlantParameters tf;
  tf.specimen_stiffness_n_per_m = 1e5;
  tf.specimen_damping_n_s_per_m = 10.0;
  tf.specimen_mass_kg = 20.0;
  const auto coupled = std::get<TransferFunctionPlantParameters>(coupled_plant_config(tf));
  EXPECT_EQ(coupled.specimen_stiffness_n_per_m, 0.0);
  EXPECT_EQ(coupled.specimen_damping_n_s_per_m, 0.0);
  EXPECT_EQ(coupled.specimen_mass_kg, 20.0);
}

}  // namespace
}  // namespace rpsd::servo
