// A servo node file whose simulated actuators carry a coupled specimen: the shipped two-actuator
// column's node (two servo-hydraulic actuators, one column coupling translation and rotation) builds
// the coupled actuator, whose load cells settle on J^-T K u by hand, the two actuators pushing
// against each other; a file whose setup or matrices do not fit the node is refused at its key.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <string>

#include "rpsd/node/actuator_factory.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/servo/coupled_specimen_actuator.h"
#include "source_dir.h"

namespace rpsd::node {
namespace {

std::filesystem::path example() { return source_dir() / "examples/nodes/two-actuator-column-site.yaml"; }

TEST(CoupledSpecimenNode, TheColumnTopNodeCarriesTheCoupledSpecimen) {
  const ServoNodeSetup setup = scenarios::load_servo_node(example());
  const auto& simulated = std::get<SimulatedActuatorParameters>(setup.actuator);
  ASSERT_TRUE(simulated.coupled_specimen.has_value());
  EXPECT_EQ(simulated.coupled_specimen->geometry.dof_count, 2);
  EXPECT_EQ(simulated.coupled_specimen->stiffness(0, 1), 0.75e6);
  EXPECT_EQ(simulated.coupled_specimen->damping(1, 1), 0.0);  // none given
  OwnedActuator owned = make_actuator(setup.actuator, setup.node.channels);
  auto* coupled = dynamic_cast<servo::CoupledSpecimenActuator*>(owned.actuator.get());
  ASSERT_NE(coupled, nullptr);
  owned.actuator->start(setup.initial_displacement_m);
  // A translation of 10 mm, ramped over 0.5 s and held: the column's top would rotate, which
  // the actuator 0.5 m above resists (pulls) while the one at the top pushes harder
  // (Jᵀ f = K u with J = [[1, 0], [1, -0.5]] near the reference configuration).
  const double period_s = setup.node.control_period_s, x = 0.01;
  servo::ActuatorReading reading;
  for (int n = 1; n <= 3072; ++n) {
    const double s = x * std::min(1.0, n * period_s / 0.5);
    const std::array<double, 2> command = {s, s};
    ASSERT_EQ(owned.actuator->exchange(command, period_s, reading), servo::ActuatorStatus::kOk) << "period " << n;
  }
  const setups::SetupVector& u = coupled->dof_displacements();
  const double force_x = 1.0e6 * u[0] + 0.75e6 * u[1], moment = 0.75e6 * u[0] + 0.75e6 * u[1];
  const double upper = -moment / 0.5, lower = force_x - upper;
  EXPECT_NEAR(reading.force_n[1], upper, 0.01 * std::abs(upper));
  EXPECT_NEAR(reading.force_n[0], lower, 0.01 * std::abs(upper));
  EXPECT_GT(reading.force_n[0], 0.0);
  EXPECT_LT(reading.force_n[1], 0.0);
}

// A copy of the example with one line replaced, in the temporary folder (its files named by
// their absolute paths).
std::string refusal(const std::string& from, const std::string& to) {
  std::ifstream in(example());
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  for (const std::string relative : {"../servo/mts-244-loading-beam.yaml", "../../transport/config/loopback.xml"}) {
    text.replace(text.find(relative), relative.size(), (example().parent_path() / relative).string());
  }
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("rpsd-coupled-node-test-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << text;
  std::string message;
  try {
    scenarios::load_servo_node(file);
  } catch (const scenarios::ConfigError& e) {
    message = e.what();
  }
  std::filesystem::remove(file);
  return message;
}

TEST(CoupledSpecimenNode, ASetupOrMatrixThatDoesNotFitIsRefusedAtItsKey) {
  const std::string rows =
      refusal("stiffness_n_per_m: [[1.0e6, 0.75e6], [0.75e6, 0.75e6]]", "stiffness_n_per_m: [1e6]");
  EXPECT_NE(rows.find("actuator.coupled_specimen.stiffness_n_per_m: needs one row per DOF"), std::string::npos) << rows;
  const std::string kind = refusal("kind: two_actuators", "kind: two_actuator");
  EXPECT_NE(kind.find("actuator.coupled_specimen.setup.kind"), std::string::npos) << kind;
  const std::string lever = refusal("distance_between_actuators_m: 0.5", "distance_between_actuators_m: 0");
  EXPECT_NE(lever.find("actuator.coupled_specimen.setup"), std::string::npos) << lever;
  const std::string channels =
      refusal("channels: 2\n  initial_displacement_m: [0, 0]", "channels: 3\n  initial_displacement_m: [0, 0, 0]");
  EXPECT_NE(channels.find("drives 2 DOFs with as many actuators, the node has 3 channels"), std::string::npos)
      << channels;
}

}  // namespace
}  // namespace rpsd::node
