// The site OpenSees talks to, driven through its site interface as the session drives it:
// a two-node spring's actuator follows the relative displacement and its force goes back
// equal and opposite; one command per moved trial; a trial beyond the rig never reaches the
// actuator; a step OpenSees and the site disagree on stops the test with both numbers.
#include "rpsd/site_server/site_server.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <future>

#include "../opensees/peer.h"
#include "rpsd/opensees/protocol.h"

#include "rpsd/hybrid_test/actuator_links.h"

namespace rpsd::site_server {
namespace {

constexpr double kRateHz = 1024.0, kPeriodS = 1.0 / kRateHz, kSpringNPerM = 1000.0;

// A perfect actuator (ideal delay 0) on a spring, on a rig of +/- 10 mm.
SiteServerConfig spring_site(int element_dofs, ChannelMap map) {
  SiteServerConfig c;
  c.name = "spring";
  c.element_dofs = element_dofs;
  c.maps = {map};
  hybrid_test::ExperimentalChannel channel;
  channel.dof.dof = map.basic_dof;
  channel.dof.specimen_stiffness_estimate_n_per_m = kSpringNPerM;
  c.site.experimental = {channel};
  servo::PureDelayParameters plant;
  plant.specimen_stiffness_n_per_m = kSpringNPerM;
  plant.rig = {0.01, 1e6, 10.0};
  c.site.plant = plant;
  c.site.control_rate_hz = kRateHz;
  return c;
}

std::filesystem::path scratch_csv(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("rpsd-site-server-" + name + ".csv");
}

TEST(SiteServer, ATwoNodeSpringFollowsTheRelativeDisplacementAndPushesBothEndsApart) {
  const SiteServerConfig config = spring_site(2, {1, 0});
  SiteServer site(config, scratch_csv("two-node"));
  const std::vector<double> d{0.001, 0.004}, zero{0.0, 0.0};
  ASSERT_TRUE(site.set_trial(d, zero, zero, kPeriodS));
  std::vector<double> force(2);
  ASSERT_TRUE(site.force(force));
  // k (d1 - d0) = 1000 N/m x 3 mm on node j, its opposite on node i.
  EXPECT_NEAR(force[1], 3.0, 1e-12);
  EXPECT_NEAR(force[0], -3.0, 1e-12);
  std::vector<double> k(4);
  site.stiffness(k);
  EXPECT_EQ(k, (std::vector<double>{kSpringNPerM, -kSpringNPerM, -kSpringNPerM, kSpringNPerM}));
}

TEST(SiteServer, ATrialThatMovesNothingIsNotAnotherCommand) {
  const SiteServerConfig config = spring_site(1, {0, -1});
  SiteServer site(config, scratch_csv("moves"));
  const std::vector<double> zero{0.0};
  std::vector<double> force(1);
  // NewmarkExplicit: the predictor and the corrector carry the same displacement.
  for (int step = 1; step <= 3; ++step) {
    const std::vector<double> d{0.001 * step};
    for (int twice = 0; twice < 2; ++twice) {
      ASSERT_TRUE(site.set_trial(d, zero, zero, step * kPeriodS));
      ASSERT_TRUE(site.force(force));
    }
  }
  EXPECT_EQ(site.run().exchanges, 3);
  EXPECT_NEAR(force[0], 3.0, 1e-12);
}

TEST(SiteServer, ATrialBeyondTheRigsStrokeNeverReachesTheActuator) {
  const SiteServerConfig config = spring_site(1, {0, -1});
  SiteServer site(config, scratch_csv("stroke"));
  const std::vector<double> zero{0.0}, beyond{0.02};
  std::vector<double> force(1);
  ASSERT_TRUE(site.set_trial(beyond, zero, zero, kPeriodS));
  EXPECT_FALSE(site.force(force));
  EXPECT_EQ(site.run().limit_stop.kind, coordinator::LimitStop::Kind::kStroke);
  EXPECT_EQ(site.run().exchanges, 0);
  EXPECT_EQ(site.actuators().simulated_plant(0)->measure().displacement_m, 0.0);  // held at rest
  // Stopped: no later trial is taken either.
  EXPECT_FALSE(site.set_trial(zero, zero, zero, 2 * kPeriodS));
}

TEST(SiteServer, AStepOfAnotherLengthStopsTheTestWithBothRates) {
  const SiteServerConfig config = spring_site(1, {0, -1});
  SiteServer site(config, scratch_csv("rate"));
  const std::vector<double> zero{0.0}, d{0.001};
  EXPECT_FALSE(site.set_trial(d, zero, zero, 0.01));
  EXPECT_THAT(site.run().stop_text, testing::HasSubstr("OpenSees stepped 0.01 s"));
  EXPECT_THAT(site.run().stop_text, testing::HasSubstr("give the OpenSees analysis dt = 0.0009765625"));
  EXPECT_EQ(site.run().exchanges, 0);
}

TEST(SiteServer, ATrialTimeThatIsNeitherTheStepsNorTheNextIsRefusedAndNeverCommanded) {
  const SiteServerConfig config = spring_site(1, {0, -1});
  SiteServer site(config, scratch_csv("time"));
  const std::vector<double> zero{0.0}, d1{0.001}, d1_iterated{0.0012}, back{0.002};
  std::vector<double> force(1);
  // The step's trial and an iteration of it (the same time, moved): both commanded.
  ASSERT_TRUE(site.set_trial(d1, zero, zero, kPeriodS));
  ASSERT_TRUE(site.force(force));
  ASSERT_TRUE(site.set_trial(d1_iterated, zero, zero, kPeriodS));
  ASSERT_TRUE(site.force(force));
  EXPECT_EQ(site.run().exchanges, 2);
  // Then a period back.
  EXPECT_FALSE(site.set_trial(back, zero, zero, 0.0));
  EXPECT_FALSE(site.force(force));
  EXPECT_THAT(site.run().stop_text, testing::HasSubstr("OpenSees' trial time went back 0.0009765625 s"));
  EXPECT_EQ(site.run().exchanges, 2);
  EXPECT_NEAR(site.actuators().simulated_plant(0)->measure().displacement_m, 0.0012, 1e-12);  // held
}

TEST(SiteServer, TrialTimesRunningBackwardsFromTheStartAreRefused) {
  const SiteServerConfig config = spring_site(1, {0, -1});
  SiteServer site(config, scratch_csv("backwards"));
  const std::vector<double> zero{0.0}, d{0.001};
  std::vector<double> force(1);
  EXPECT_FALSE(site.set_trial(d, zero, zero, -kPeriodS));
  EXPECT_FALSE(site.force(force));
  EXPECT_THAT(site.run().stop_text, testing::HasSubstr("from t = 0 s to -0.0009765625 s"));
  EXPECT_EQ(site.run().exchanges, 0);
  EXPECT_EQ(site.actuators().simulated_plant(0)->measure().displacement_m, 0.0);
}

TEST(SiteServer, AClientThatLeavesMidStepLeavesTheActuatorWhereItsLastCommandPutIt) {
  const SiteServerConfig config = spring_site(1, {0, -1});
  SiteServer site(config, scratch_csv("leaves"));
  opensees::TcpListener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [&] {
    opensees::TcpStream c = opensees::TcpStream::connect("127.0.0.1", listener.port(), 5.0);
    opensees::test::write_ints(c, opensees::generic_client_sizes(1).to_wire());
    for (int n = 1; n <= 3; ++n) {
      opensees::test::write_request(c, 256, {opensees::kSetTrialResponse, 0.001 * n, 0.0, 0.0, n * kPeriodS});
      opensees::test::write_request(c, 256, {opensees::kGetForce});
      (void)opensees::test::read_reply(c, 256);
    }
    // The fourth step's trial, and then the client is gone before asking for its force.
    opensees::test::write_request(c, 256, {opensees::kSetTrialResponse, 0.009, 0.0, 0.0, 4 * kPeriodS});
  });
  const SiteRun run = site.serve(*listener.accept(5.0), {});
  client.get();
  EXPECT_EQ(run.end.kind, opensees::SessionEnd::Kind::kClosed);
  EXPECT_EQ(run.exchanges, 3);
  // Held at the third command (3 mm), never sent toward the fourth trial's 9 mm.
  EXPECT_NEAR(site.actuators().simulated_plant(0)->measure().displacement_m, 0.003, 1e-12);
}

}  // namespace
}  // namespace rpsd::site_server
