// The dry run of a test with a held force (examples/scenarios/column-axial-load.yaml): its
// report carries the held force's ramp and limits, and a node file for its site must have one
// channel more than the site's structure channels, declared in force control, or the check
// refuses it before anything moves.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/studies/dry_run.h"

namespace rpsd::studies {
namespace {

hybrid_test::TestConfig column() {
  return std::get<hybrid_test::TestConfig>(
      scenarios::load_study(testing::source_dir() / "examples/scenarios/column-axial-load.yaml",
                            {scenarios::parse_override("ground_motion.trim={end_s: 1}")})
          .study);
}

// The example's node file as `rpsd run --dry-run --node FILE` takes it.
NodeLimits column_node(std::vector<scenarios::Override> overrides = {}) {
  const node::ServoNodeSetup n =
      scenarios::load_servo_node(testing::source_dir() / "examples/nodes/column-axial-load-site.yaml", overrides);
  NodeLimits limits;
  limits.name = "column-axial-load-site.yaml";
  limits.test_id = n.node.test_id;
  limits.site_id = n.node.site_id;
  limits.control_period_s = n.node.control_period_s;
  limits.channels.assign(n.node.limits.begin(), n.node.limits.begin() + n.node.channels);
  limits.control.assign(n.node.control.begin(), n.node.control.begin() + n.node.channels);
  return limits;
}

TEST(DryRunHeldForces, TheReportCarriesEachHeldForcesRampAndLimits) {
  const DryRunReport r = dry_run(column(), {column_node()});
  ASSERT_EQ(r.held_forces.size(), 1u);
  const HeldForcePrediction& h = r.held_forces[0];
  EXPECT_EQ(h.name, "site 1 held force axial");
  EXPECT_EQ(h.channel, 1);
  EXPECT_DOUBLE_EQ(h.force_n, -30.0e3);
  EXPECT_DOUBLE_EQ(h.ramp_s, 3.0);
  EXPECT_DOUBLE_EQ(h.limits.max_force_n, 40.0e3);
  EXPECT_DOUBLE_EQ(h.limits.max_stroke_m, 0.08);
  ASSERT_TRUE(r.channels[0].node.has_value());  // the node's channel 0 is the structure's
}

TEST(DryRunHeldForces, ANodeFileMustDeclareTheHeldForcesChannelInForceControl) {
  EXPECT_THAT(
      [] {
        (void)dry_run(column(),
                      {column_node({scenarios::parse_override("actuator.control=[displacement, displacement]")})});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr(
          "channel 1 is in displacement control (actuator.control), the scenario sends it the force of site 1 "
          "held force axial: declare it force")));
  EXPECT_THAT(
      [] {
        (void)dry_run(column(), {column_node({scenarios::parse_override("actuator.channels=1"),
                                              scenarios::parse_override("actuator.control=[displacement]"),
                                              scenarios::parse_override("limits={max_stroke_m: [0.1]}")})});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(
          ::testing::HasSubstr("1 channel(s), the scenario gives site 1 2 (1 of them holding a force)")));
}

}  // namespace
}  // namespace rpsd::studies
