// An in-process site whose setup carries a coupled specimen: its node drives one simulated
// actuator per setup actuator under that one specimen, with the setup's actuators on the
// site's channels however the test numbers them, its load cells at rest and after a command
// against J^-T K u by hand, in the test and in its perfect-actuator reference alike.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "rpsd/hybrid_test/site_kinds.h"

namespace rpsd::hybrid_test {
namespace {

constexpr double kLever_m = 0.8;

// A column top: the bottom actuator at the control point drives x, the top one kLever_m above
// it; linear: s_bottom = x, s_top = x - h θ. The test puts θ on channel 0 and x on channel 1,
// so the setup's actuators (bottom on x's channel 1, top on θ's channel 0) are in the opposite
// order to the site's channels.
ExperimentalSetupSite column_top() {
  setups::PlanarActuatorsParameters planar;
  planar.geometry.dof_count = 2;
  planar.geometry.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation,
                          setups::DofMotion::kTranslationY};
  planar.geometry.actuators[0] = {"bottom", {-2.0, 0.0}, {0.0, 0.0}};
  planar.geometry.actuators[1] = {"top", {-2.0, kLever_m}, {0.0, kLever_m}};
  ExperimentalSetupSite site;
  site.site_id = 1;
  site.channels = {1, 0};
  site.setup = planar;
  site.specimen_stiffness.resize(2, 2);
  site.specimen_stiffness << 1.5e6, -1.5e6, -1.5e6, 2.0e6;
  return site;
}

// The actuators' loads in the site's channel order (top, bottom) at x, θ: Jᵀ f = K u with
// J = [[1, 0], [1, -h]] (rows bottom, top).
std::vector<double> hand_loads(double x, double theta) {
  const double force_x = 1.5e6 * x - 1.5e6 * theta, moment = -1.5e6 * x + 2.0e6 * theta;
  const double top = -moment / kLever_m;
  return {top, force_x - top};
}

TestConfig coupled_test(const servo::PlantConfig& plant) {
  TestConfig config;
  config.plant = plant;
  config.setups = {column_top()};
  return config;
}

SiteSetup site_at(double x, double theta, bool perfect_actuator) {
  SiteSetup setup;
  setup.site_id = 1;
  setup.channels = {0, 1};
  setup.hold_m = {x - kLever_m * theta, x};  // top, bottom: the strokes at rest
  setup.stiffness_estimate_n_per_m = {2.0e6, 1.5e6};
  setup.control_period_s = 1.0 / 1024.0;
  setup.run_id = 7;
  setup.perfect_actuator = perfect_actuator;
  return setup;
}

TEST(CoupledSite, LoadCellsCarryTheCoupledSpecimenAtRestAndAfterACommand) {
  // The test's plant follows its command; its own specimen (k = 4e5) must not count.
  servo::PureDelayParameters plant{0.0, 4e5, 8192.0, {}, {}};
  for (const bool perfect : {false, true}) {
    const TestConfig config = coupled_test(plant);
    SiteSetup setup = site_at(0.002, 0.001, perfect);
    SiteResources shared;
    const auto site = make_site(config, setup, shared);
    const std::vector<double> at_rest = hand_loads(0.002, 0.001);
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_NEAR(site->initial_force_n(j), at_rest[j], 1e-6) << "channel " << j << (perfect ? " (perfect)" : "");
    }
    transport::CommandSample command;
    command.test_id = config.transport.test_id;
    command.site_id = 1;
    command.run_id = setup.run_id;
    command.channels = 2;
    const double x = 0.003, theta = -0.0005;
    command.displacement_m[0] = x - kLever_m * theta;
    command.displacement_m[1] = x;
    transport::FeedbackSample feedback;
    for (int step = 0; step < 3; ++step) {
      command.step = step;
      ASSERT_EQ(site->link().send(command), transport::LinkStatus::kOk);
      ASSERT_EQ(site->link().receive(feedback), transport::LinkStatus::kOk);
    }
    ASSERT_EQ(feedback.status & transport::kNodeFault, 0u);
    const std::vector<double> loads = hand_loads(x, theta);
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_NEAR(feedback.force_n[j], loads[j], 1e-6) << "channel " << j << (perfect ? " (perfect)" : "");
    }
  }
}

TEST(CoupledSite, APlantThatCannotCarryTheSpecimenIsRefusedNamingTheSite) {
  servo::FeedbackControlledPlantParameters loop;
  loop.plant.transfer_function = {servo::Polynomial{100.0}, servo::Polynomial{100.0, 1.0}};
  const TestConfig config = coupled_test(loop);
  SiteSetup setup = site_at(0.0, 0.0, false);
  SiteResources shared;
  try {
    make_site(config, setup, shared);
    FAIL() << "a feedback-controlled plant under a coupled specimen was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("site 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("feedback_controlled"), std::string::npos) << e.what();
  }
}

TEST(CoupledSite, WithoutASpecimenMatrixEachChannelKeepsItsOwnSpecimen) {
  servo::PureDelayParameters plant{0.0, 4e5, 8192.0, {}, {}};
  TestConfig config = coupled_test(plant);
  config.setups[0].specimen_stiffness.resize(0, 0);
  SiteSetup setup = site_at(0.002, 0.001, false);
  SiteResources shared;
  const auto site = make_site(config, setup, shared);
  EXPECT_NEAR(site->initial_force_n(0), 4e5 * setup.hold_m[0], 1e-9);
  EXPECT_NEAR(site->initial_force_n(1), 4e5 * setup.hold_m[1], 1e-9);
}

// The perfect-actuator reference has no limits to keep a command out of reach: strokes no
// configuration has fault its node, which says why.
TEST(CoupledSite, StrokesTheGeometryCannotSolveFaultTheNodeWhichSaysWhy) {
  TestConfig config = coupled_test(servo::PureDelayParameters{});
  std::get<setups::PlanarActuatorsParameters>(config.setups[0].setup).geometry.geometry =
      setups::Geometry::kLargeDisplacement;
  SiteSetup setup = site_at(0.0, 0.0, true);
  SiteResources shared;
  const auto site = make_site(config, setup, shared);
  transport::CommandSample command;
  command.test_id = config.transport.test_id;
  command.site_id = 1;
  command.run_id = setup.run_id;
  command.channels = 2;
  command.displacement_m[0] = -6.0;  // the top actuator 4 m shorter than nothing
  transport::FeedbackSample feedback;
  ASSERT_EQ(site->link().send(command), transport::LinkStatus::kOk);
  site->link().receive(feedback);
  EXPECT_NE(feedback.status & transport::kNodeFault, 0u);
  EXPECT_NE(site->node_fault_text().find("coupled specimen"), std::string::npos) << site->node_fault_text();
}

}  // namespace
}  // namespace rpsd::hybrid_test
