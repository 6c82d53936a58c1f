// A scenario's experimental_setups: a site whose DOFs several actuators drive through their
// geometry. What the file says reaches the test's configuration, and what cannot work is
// refused at its key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/substructure/partition.h"

namespace rpsd::scenarios {
namespace {

const std::filesystem::path kColumn = testing::source_dir() / "examples/scenarios/two-actuator-column.yaml";

hybrid_test::TestConfig column(std::vector<Override> overrides = {}) {
  return std::get<hybrid_test::TestConfig>(load_study(kColumn, overrides).study);
}

void refused(const std::string& override_text, const std::string& words) {
  EXPECT_THAT([&] { (void)column({parse_override(override_text)}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr(words)))
      << override_text;
}

TEST(ExperimentalSetupsFile, TheSetupTakesItsSitesDofsInItsOrderOnTheirChannels) {
  const hybrid_test::TestConfig t = column();
  ASSERT_EQ(t.setups.size(), 1u);
  const hybrid_test::ExperimentalSetupSite& s = t.setups[0];
  EXPECT_EQ(s.site_id, 1u);
  EXPECT_EQ(s.channels, (std::vector<int>{0, 1}));
  EXPECT_EQ(config::kind_name(s.setup), "two_actuators");
  const setups::PlanarGeometry g = setups::planar_geometry(s.setup);
  EXPECT_EQ(g.geometry, setups::Geometry::kLargeDisplacement);
  EXPECT_EQ(g.dofs[0], setups::DofMotion::kTranslationX);
  EXPECT_EQ(g.dofs[1], setups::DofMotion::kRotation);
  EXPECT_EQ(s.compensated, hybrid_test::ExperimentalSetupSite::Compensated::kActuators);
  ASSERT_EQ(s.actuator_limits.size(), 2u);
  EXPECT_DOUBLE_EQ(s.actuator_limits[1].max_force_n, 120.0e3);
  EXPECT_DOUBLE_EQ(s.actuator_limits[1].max_velocity_m_per_s, 0.5);
  EXPECT_DOUBLE_EQ(s.max_calibration_offset_m, 0.002);
  ASSERT_EQ(s.specimen_stiffness.rows(), 2);
  EXPECT_DOUBLE_EQ(s.specimen_stiffness(0, 1), 0.75e6);
  EXPECT_EQ(s.specimen_damping.size(), 0);
}

TEST(ExperimentalSetupsFile, ADofsOrderFollowsTheListNotTheEntries) {
  // The setup's DOF 0 is the structure's DOF 1 now: its actuator 0 answers on DOF 1's channel.
  const hybrid_test::TestConfig t = column({parse_override("experimental_setups.0.dofs=[1, 0]"),
                                            parse_override("experimental.1.limits={max_stroke_m: 0.05}"),
                                            parse_override("experimental.0.limits={max_rotation_rad: 0.05}")});
  EXPECT_EQ(t.setups[0].channels, (std::vector<int>{1, 0}));
}

TEST(ExperimentalSetupsFile, ARotationDofTakesItsLimitsInRadiansAndNewtonMetres) {
  const hybrid_test::TestConfig t = column();
  EXPECT_DOUBLE_EQ(t.experimental[1].limits.max_stroke_m, 0.05);   // max_rotation_rad
  EXPECT_DOUBLE_EQ(t.experimental[1].limits.max_force_n, 60.0e3);  // max_moment_n_m
  refused("experimental.1.limits={max_stroke_m: 0.05}", "experimental[1].limits.max_stroke_m");
  refused("experimental.0.limits={max_rotation_rad: 0.05}", "experimental[0].limits.max_rotation_rad");
  refused("experimental.1.limits={max_rotation_rate_rad_per_s: 0.1, max_rotation_increment_rad: 0.001}",
          "experimental[1].limits.max_rotation_rate_rad_per_s: give max_rotation_increment_rad or");
  refused("experimental.0.limits={max_velocity_m_per_s: 0.1, max_increment_m: 0.001}",
          "experimental[0].limits.max_velocity_m_per_s: give max_increment_m or");
}

TEST(ExperimentalSetupsFile, TheSpecimensDiagonalIsEachDofsEstimateAndItsCouplingEntersK0) {
  const hybrid_test::TestConfig t = column();
  EXPECT_DOUBLE_EQ(t.experimental[0].dof.specimen_stiffness_estimate_n_per_m, 1.0e6);
  EXPECT_DOUBLE_EQ(t.experimental[1].dof.specimen_stiffness_estimate_n_per_m, 0.75e6);
  const substructure::PartitionConfig p = hybrid_test::partition_config(t, 3);
  ASSERT_EQ(p.couplings.size(), 1u);
  EXPECT_EQ(p.couplings[0].channel_a, 0);
  EXPECT_EQ(p.couplings[0].channel_b, 1);
  EXPECT_DOUBLE_EQ(p.couplings[0].stiffness_n_per_m, 0.75e6);
}

TEST(ExperimentalSetupsFile, ACouplingIsScaledLikeTheForcesAndDisplacementsItJoins) {
  // A half-scale specimen: the translation's force scale 4, the rotation's moment scale 8,
  // the translation's displacement scale 0.5: K_model(0, 1) = 4 x 1 x k, K_model(1, 0) = 8 x 0.5 x k.
  const hybrid_test::TestConfig t =
      column({parse_override("experimental.0.force_scale=4"), parse_override("experimental.0.displacement_scale=0.5"),
              parse_override("experimental.1.force_scale=8")});
  const substructure::PartitionConfig p = hybrid_test::partition_config(t, 3);
  ASSERT_EQ(p.couplings.size(), 1u);
  EXPECT_DOUBLE_EQ(p.couplings[0].stiffness_n_per_m, 4.0 * 0.75e6);
}

TEST(ExperimentalSetupsFile, WhatCannotWorkIsRefusedAtItsKey) {
  refused("experimental_setups.0.dofs=[0]", "experimental_setups[0].dofs: the two_actuators setup drives 2 DOF(s)");
  refused("experimental_setups.0.dofs=[0, 0]", "experimental_setups[0].dofs: DOF 0 is listed twice");
  refused("experimental_setups.0.site=2", "DOF 0 is no experimental[] entry of site 2");
  refused("experimental_setups.0.setup.kind=two_actuator", "experimental_setups[0].setup.kind");
  refused("experimental_setups.0.setup.distance_between_actuators_m=0", "experimental_setups[0].setup");
  refused("experimental_setups.0.actuator_limits=[{max_force_n: 1000}]", "experimental_setups[0].actuator_limits");
  refused("experimental_setups.0.specimen.stiffness_n_per_m=[[1e6, 0.7e6], [0.75e6, 0.75e6]]",
          "experimental_setups[0].specimen.stiffness_n_per_m: must be symmetric");
  refused("experimental_setups.0.specimen.stiffness_n_per_m=[1e6]", "needs 2 rows of 2");
  refused("experimental.0.specimen_stiffness_n_per_m=1e6", "takes its specimen from the setup's `specimen`");
  refused("experimental.0.restoring_force=stiffness_times_displacement", "from the actuators' load cells");
}

TEST(ExperimentalSetupsFile, AnActuatorsLimitBeyondTheRigIsRefusedAtItsKey) {
  // The paper's MTS 244: 156 kN, +/-127 mm.
  refused("experimental_setups.0.actuator_limits.1.max_force_n=200e3",
          "experimental_setups[0].actuator_limits[1].max_force_n");
  refused("experimental_setups.0.actuator_limits.0.max_stroke_m=0.2",
          "experimental_setups[0].actuator_limits[0].max_stroke_m");
}

TEST(ExperimentalSetupsFile, ADofDrivenTwiceIsRefused) {
  // The example with a second setup that drives DOF 0 again.
  std::ifstream in(kColumn);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string anchor = "experimental_setups:\n";
  text.insert(text.find(anchor) + anchor.size(),
              "  - {site: 1, dofs: [0], setup: {kind: one_actuator, geometry: linear, dof: translation_x, "
              "actuator_length_m: 1.0},\n"
              "     specimen: {stiffness_n_per_m: 1e6}}\n");
  // Beside no example: its files named absolute.
  for (const std::string relative : {"../../", "../"}) {
    const std::string absolute = (relative == "../" ? kColumn.parent_path().parent_path().string()
                                                    : kColumn.parent_path().parent_path().parent_path().string()) +
                                 "/";
    for (std::size_t at = text.find(": " + relative); at != std::string::npos; at = text.find(": " + relative, at)) {
      text.replace(at + 2, relative.size(), absolute);
    }
  }
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "rpsd-two-setups-on-one-dof.yaml";
  std::ofstream(file) << text;
  EXPECT_THAT([&] { (void)load_study(file); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr(
                  "experimental_setups[1].dofs: DOF 0 is driven by another experimental setup too")));
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace rpsd::scenarios
