// A servo node file whose simulated actuators carry a coupled specimen: the shipped column-top
// node (two servo-hydraulic actuators, one specimen coupling translation and rotation) builds
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

namespace rpsd::node {
namespace {

std::filesystem::path source_dir() {
  if (const char* env = std::getenv("RPSD_SOURCE_DIR"); env != nullptr && *env != '\0') return env;
  return RPSD_TEST_SOURCE_DIR;
}

std::filesystem::path example() { return source_dir() / "examples/nodes/column-top-coupled-node.yaml"; }

TEST(CoupledSpecimenNode, TheColumnTopNodeCarriesTheCoupledSpecimen) {
  const ServoNodeSetup setup = scenarios::load_servo_node(example());
  const auto& simulated = std::get<SimulatedActuatorParameters>(setup.actuator);
  ASSERT_TRUE(simulated.coupled_specimen.has_value());
  EXPECT_EQ(simulated.coupled_specimen->geometry.dof_count, 2);
  EXPECT_EQ(simulated.coupled_specimen->stiffness(0, 1), -1.5e6);
  EXPECT_EQ(simulated.coupled_specimen->damping(1, 1), 1.0e4);
  OwnedActuator owned = make_actuator(setup.actuator, setup.node.channels);
  auto* coupled = dynamic_cast<servo::CoupledSpecimenActuator*>(owned.actuator.get());
  ASSERT_NE(coupled, nullptr);
  owned.actuator->start(setup.initial_displacement_m);
  // A translation of 10 mm, ramped over 0.5 s and held: the top actuator pushes, the bottom
  // one pulls (Jᵀ f = K u with J = [[1, 0], [1, -0.8]] near the reference configuration).
  const double period_s = setup.node.control_period_s, x = 0.01;
  servo::ActuatorReading reading;
  for (int n = 1; n <= 3072; ++n) {
    const double s = x * std::min(1.0, n * period_s / 0.5);
    const std::array<double, 2> command = {s, s};
    ASSERT_EQ(owned.actuator->exchange(command, period_s, reading), servo::ActuatorStatus::kOk) << "period " << n;
  }
  const setups::SetupVector& u = coupled->dof_displacements();
  const double force_x = 1.5e6 * u[0] - 1.5e6 * u[1], moment = -1.5e6 * u[0] + 2.0e6 * u[1];
  const double top = -moment / 0.8, bottom = force_x - top;
  EXPECT_NEAR(reading.force_n[1], top, 0.01 * std::abs(top));
  EXPECT_NEAR(reading.force_n[0], bottom, 0.01 * std::abs(top));
  EXPECT_LT(reading.force_n[0], 0.0);
  EXPECT_GT(reading.force_n[1], 0.0);
}

// A copy of the example with one line replaced, in the temporary folder (its files named by
// their absolute paths).
std::string refusal(const std::string& from, const std::string& to) {
  std::ifstream in(example());
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  for (const std::string relative : {"../servo/paper-mts-244.yaml", "../../transport/config/loopback.xml"}) {
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
  EXPECT_NE(refusal("damping: [2.0e4, 1.0e4]", "damping: [2.0e4]").find("actuator.coupled_specimen.damping"),
            std::string::npos);
  EXPECT_NE(refusal("dofs: [translation_x, rotation]", "dofs: [translation_x, twist]").find("'twist'"),
            std::string::npos);
  const std::string lever = refusal("fixed_end_m: [-2.0, 0.8], attachment_m: [0.0, 0.8]",
                                    "fixed_end_m: [-2.0, 0.0], attachment_m: [0.0, 0.0]");
  EXPECT_NE(lever.find("actuator.coupled_specimen.setup.actuators"), std::string::npos) << lever;
  EXPECT_NE(lever.find("singular"), std::string::npos) << lever;
}

}  // namespace
}  // namespace rpsd::node
