// The site's real-time path allocates nothing: each OpenSees step (a trial, its force
// request: compensation, limits, the in-process node, the recorder) and each request the
// session serves after its setup.
#include <gtest/gtest.h>

#include <filesystem>
#include <future>

#include "../opensees/peer.h"
#include "../support/allocation_counter.h"
#include "rpsd/opensees/protocol.h"
#include "rpsd/site_server/site_server.h"

namespace rpsd::site_server {
namespace {

constexpr double kPeriodS = 1.0 / 1024.0;

SiteServerConfig spring_site() {
  SiteServerConfig c;
  c.name = "spring";
  c.element_dofs = 1;
  c.maps = {{0, -1}};
  hybrid_test::ExperimentalChannel channel;
  channel.dof.specimen_stiffness_estimate_n_per_m = 1000.0;
  c.site.experimental = {channel};
  servo::PureDelayParameters plant;
  plant.delay_s = 0.002;
  plant.specimen_stiffness_n_per_m = 1000.0;
  plant.rig = {0.1, 1e6, 10.0};
  c.site.plant = plant;
  c.site.control_rate_hz = 1024.0;
  return c;
}

std::filesystem::path csv(const char* name) { return std::filesystem::temp_directory_path() / name; }

TEST(SiteAllocation, AnOpenSeesStepThroughTheSiteAllocatesNothing) {
  const SiteServerConfig config = spring_site();
  SiteServer site(config, csv("rpsd-site-allocation.csv"));
  std::vector<double> d(1), zero(1, 0.0), force(1);
  const auto step = [&](int n) {
    d[0] = 0.001 * std::sin(0.01 * n);
    return site.set_trial(d, zero, zero, n * kPeriodS) && site.force(force);
  };
  for (int n = 1; n <= 10; ++n) ASSERT_TRUE(step(n));
  testing::begin_counting_allocations();
  bool ok = true;
  for (int n = 11; n <= 2000; ++n) ok = ok && step(n);
  const testing::AllocationCounts counts = testing::end_counting_allocations();
  ASSERT_TRUE(ok);
  EXPECT_EQ(counts.total(), 0) << counts.operator_new << " new, " << counts.c_allocations << " malloc";
}

// Everything the serving thread allocates for a client of `steps` steps.
long allocations_serving(int steps) {
  const SiteServerConfig config = spring_site();
  SiteServer site(config, csv("rpsd-session-allocation.csv"));
  opensees::TcpListener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [&] {
    opensees::TcpStream c = opensees::TcpStream::connect("127.0.0.1", listener.port(), 5.0);
    opensees::test::write_ints(c, opensees::generic_client_sizes(1).to_wire());
    for (int n = 1; n <= steps; ++n) {
      const double t = n * kPeriodS, d = 0.001 * std::sin(0.01 * n);
      opensees::test::write_request(c, 256, {opensees::kSetTrialResponse, d, 0.0, 0.0, t});
      opensees::test::write_request(c, 256, {opensees::kGetDamp});
      (void)opensees::test::read_reply(c, 256);
      opensees::test::write_request(c, 256, {opensees::kGetForce});
      (void)opensees::test::read_reply(c, 256);
      opensees::test::write_request(c, 256, {opensees::kCommitState});
    }
    opensees::test::write_request(c, 256, {opensees::kDie});
  });
  opensees::TcpStream stream = *listener.accept(5.0);
  testing::begin_counting_allocations();
  const SiteRun run = site.serve(std::move(stream), {});
  const long total = testing::end_counting_allocations().total();
  client.get();
  EXPECT_EQ(run.end.kind, opensees::SessionEnd::Kind::kDie);
  EXPECT_EQ(run.exchanges, steps);
  return total;
}

TEST(SiteAllocation, ARequestAfterTheSetupAllocatesNothing) {
  // The setup and the end allocate the same whatever the length: any difference is per request.
  EXPECT_EQ(allocations_serving(50), allocations_serving(500));
}

}  // namespace
}  // namespace rpsd::site_server
