// The OpenSees keys: a scenario's opensees_sites (numerical sites behind adapter elements)
// and the site-server file, refused with the key when they cannot work.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::scenarios {
namespace {

const std::filesystem::path kSplit = testing::source_dir() / "examples/opensees/three-storey-split.yaml";
const std::filesystem::path kSite = testing::source_dir() / "tests/scenarios/data/reference/site-server.yaml";

const hybrid_test::TestConfig& test_of(const studies::StudyDocument& d) {
  return std::get<hybrid_test::TestConfig>(d.study);
}

TEST(OpenSeesSites, EachDofOfASiteIsAChannelOfThatSiteAndNeedsNoSpecimenOrServo) {
  const auto d = load_study(kSplit);
  const hybrid_test::TestConfig& t = test_of(d);
  ASSERT_EQ(t.opensees_sites.size(), 1u);
  EXPECT_EQ(t.opensees_sites[0].adapter.dofs, 3);
  EXPECT_EQ(t.opensees_sites[0].reference_port, 8092);
  ASSERT_EQ(t.experimental.size(), 3u);
  EXPECT_EQ(t.experimental[2].dof.dof, 2);
  EXPECT_EQ(t.experimental[2].dof.actuator_channel, 2);
  EXPECT_EQ(t.experimental[2].site_id, 2u);
  EXPECT_DOUBLE_EQ(t.experimental[1].dof.specimen_stiffness_estimate_n_per_m, 1000e3);
  EXPECT_NE(t.opensees_site(2), nullptr);
  EXPECT_EQ(t.opensees_site(1), nullptr);
}

TEST(OpenSeesSites, TheReferenceNeedsAnotherProcess) {
  EXPECT_THAT([] { (void)load_study(kSplit, {parse_override("opensees_sites.0.reference_port=8091")}); },
              ::testing::ThrowsMessage<ConfigError>(
                  ::testing::HasSubstr("opensees_sites[0].reference_port: must differ from port")));
}

TEST(OpenSeesSites, ADofTakenTwiceIsRefused) {
  EXPECT_THAT([] { (void)load_study(kSplit, {parse_override("opensees_sites.0.dofs=[0, 1, 1]")}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("DOF 1 is taken by another site")));
}

TEST(OpenSeesSites, ARealTimeClockIsRefused) {
  EXPECT_THAT([] { (void)load_study(kSplit, {parse_override("clock.mode=real_time")}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("clock.mode as_fast_as_possible")));
}

TEST(SiteServerFile, ChannelsFollowTheirBasicDofs) {
  const site_server::SiteServerConfig c = load_site_server(kSite);
  EXPECT_EQ(c.element_dofs, 2);
  ASSERT_EQ(c.maps.size(), 1u);
  EXPECT_EQ(c.maps[0].basic_dof, 1);
  EXPECT_EQ(c.maps[0].relative_to, 0);
  EXPECT_DOUBLE_EQ(c.site.control_rate_hz, 1024.0);
  EXPECT_EQ(c.input_files.size(), 1u);
}

TEST(SiteServerFile, ABasicDofBeyondTheElementIsRefusedWithItsKey) {
  EXPECT_THAT([] { (void)load_site_server(kSite, {parse_override("element_dofs=1")}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("experimental[0].basic_dof: expected")));
}

TEST(SiteServerFile, OpenSeesPacesTheTest) {
  EXPECT_THAT([] { (void)load_site_server(kSite, {parse_override("clock.mode=real_time")}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("OpenSees paces a site server's test")));
}

TEST(SiteServerFile, ALimitBeyondTheRigIsRefused) {
  EXPECT_THAT([] { (void)load_site_server(kSite, {parse_override("experimental.0.limits.max_stroke_m=0.2")}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("max_stroke_m")));
}

// A site file's coordinator limits take the per-second increment as a scenario's do: held to
// the rig's velocity capacity (1 m/s here), never beside the per-period key.
TEST(SiteServerFile, AnIncrementPerSecondIsHeldToTheRigAndNeverBesideThePerPeriodOne) {
  const auto c = load_site_server(kSite, {parse_override("experimental.0.limits.max_velocity_m_per_s=0.5")});
  EXPECT_EQ(c.site.experimental[0].limits.max_velocity_m_per_s, 0.5);
  EXPECT_THAT([] { (void)load_site_server(kSite, {parse_override("experimental.0.limits.max_velocity_m_per_s=1.5")}); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr(
                  "experimental[0].limits.max_velocity_m_per_s: 1.5 is beyond the rig's velocity capacity of 1")));
  EXPECT_THAT(
      [] {
        (void)load_site_server(kSite, {parse_override("experimental.0.limits={max_velocity_m_per_s: 0.5, "
                                                      "max_increment_m: 0.0001}")});
      },
      ::testing::ThrowsMessage<ConfigError>(
          ::testing::HasSubstr("experimental[0].limits.max_velocity_m_per_s: give max_increment_m")));
}

}  // namespace
}  // namespace rpsd::scenarios
