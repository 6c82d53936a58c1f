// The site factory: one list of site kinds, the first that serves a site builds it, and one
// SiteSetup::complete() gives an in-process node the rig's envelope and the force guard's
// stiffness (the stiffest of the plant's specimen and the channel's estimate).
#include "rpsd/hybrid_test/site_kinds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string_view>
#include <utility>
#include <vector>

#include "rpsd/config/key_error.h"
#include "rpsd/hybrid_test/specimen_sdof.h"

namespace rpsd::hybrid_test {
namespace {

// The paper's SDOF on an ideal rig of +/-50 mm, 100 kN and 0.5 m/s, whose load cell sees
// `plant_k`, while the test estimates the specimen at `estimate_k`.
TestConfig sdof_on_rig(double plant_k, double estimate_k) {
  SpecimenSdof sdof;
  servo::PureDelayParameters plant{0.0, plant_k, 8192.0, {}, {}};
  plant.rig = {0.05, 100e3, 0.5};
  sdof.plant = plant;
  TestConfig config = specimen_sdof_test(sdof);
  config.experimental[0].dof.specimen_stiffness_estimate_n_per_m = estimate_k;
  return config;
}

SiteSetup one_channel_site(const TestConfig& config, bool perfect_actuator = false) {
  SiteSetup setup;
  setup.site_id = 1;
  setup.channels = {0};
  setup.hold_m = {0.0};
  setup.stiffness_estimate_n_per_m = {config.experimental[0].dof.specimen_stiffness_estimate_n_per_m};
  setup.control_period_s = 1.0 / config.control_rate_hz;
  setup.perfect_actuator = perfect_actuator;
  return setup;
}

TEST(SiteKinds, ListedOnceInTheOrderTheyAreTried) {
  const std::vector<std::string_view> expected{"opensees_adapter", "dds", "in_process"};
  EXPECT_EQ(SiteKinds::names(), expected);
}

TEST(SiteKinds, AnActuatorSiteInProcessTakesTheRigEnvelopeAsItsNodesLimits) {
  const TestConfig config = sdof_on_rig(700.8e3, 700.8e3);
  SiteSetup setup = one_channel_site(config);
  SiteResources shared;
  const auto site = make_site(config, setup, shared);
  ASSERT_NE(site, nullptr);
  EXPECT_NE(site->simulated_plant(0), nullptr);  // the in-process kind built it
  EXPECT_FALSE(site->over_dds());
  const node::ChannelLimits& limits = setup.node.node.limits[0];
  EXPECT_EQ(limits.max_stroke_m, 0.05);
  EXPECT_EQ(limits.max_force_n, 100e3);
  EXPECT_EQ(limits.max_velocity_m_per_s, 0.5);
  EXPECT_EQ(setup.node.node.rig[0].stroke_m, 0.05);
}

TEST(SiteKinds, TheForceGuardPredictsWithTheStiffestSpecimenKnown) {
  for (const auto& [plant_k, estimate_k] : {std::pair{700.8e3, 2e6}, std::pair{3e6, 1e5}}) {
    const TestConfig config = sdof_on_rig(plant_k, estimate_k);
    SiteSetup setup = one_channel_site(config);
    setup.complete(config);
    EXPECT_EQ(setup.node.node.limits[0].force_guard_stiffness_n_per_m, std::max(plant_k, estimate_k));
  }
  // One the test states stands.
  TestConfig config = sdof_on_rig(700.8e3, 2e6);
  config.site_nodes[1].limits[0].force_guard_stiffness_n_per_m = 1e3;
  SiteSetup setup = one_channel_site(config);
  setup.complete(config);
  EXPECT_EQ(setup.node.node.limits[0].force_guard_stiffness_n_per_m, 1e3);
}

TEST(SiteKinds, ThePerfectActuatorReferenceHasNoRigToKeepItIn) {
  TestConfig config = sdof_on_rig(700.8e3, 700.8e3);
  config.site_nodes[1].limits[0].max_stroke_m = 0.01;  // the test's node, not the reference's
  SiteSetup setup = one_channel_site(config, true);
  setup.complete(config);
  EXPECT_EQ(setup.node.node.limits[0].max_stroke_m, node::ChannelLimits::kNone);
  EXPECT_EQ(setup.node.node.limits[0].force_guard_stiffness_n_per_m, 0.0);
}

TEST(SiteKinds, ALimitBeyondTheRigNamesItsKeyTyped) {
  TestConfig config = sdof_on_rig(700.8e3, 700.8e3);
  config.site_nodes[1].limits[0].max_force_n = 200e3;  // the rig gives 100 kN
  SiteSetup setup = one_channel_site(config);
  try {
    setup.complete(config);
    FAIL() << "a limit beyond the rig was taken";
  } catch (const config::KeyError& e) {
    EXPECT_EQ(e.path(), "limits[0].max_force_n");
    EXPECT_EQ(e.leaf(), "max_force_n");
    EXPECT_EQ(std::string(e.what()), "limits[0].max_force_n: " + e.problem());
  }
}

}  // namespace
}  // namespace rpsd::hybrid_test
