// The client of an OpenSees adapter against a scripted adapter on loopback: the sizes it
// announces are the ones Adapter.cpp checks, each step's trial and force request arrive as
// [3, d...] and [10], the reply's second half is the force, and a lost adapter is reported.
#include "rpsd/opensees/adapter_link.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <future>

#include "peer.h"
#include "rpsd/opensees/protocol.h"

namespace rpsd::opensees {
namespace {

TEST(AdapterLink, AStepSendsTheTrialAndTheForceRequestAndTakesTheSecondHalfAsForces) {
  TcpListener listener("127.0.0.1", 0);
  std::array<std::int32_t, 11> sizes{};
  std::vector<double> trial(4), request(4);
  auto adapter = std::async(std::launch::async, [&] {
    TcpStream s = *listener.accept(5.0);
    EXPECT_EQ(s.read_exact(std::as_writable_bytes(std::span<std::int32_t>(sizes)), 5.0, 5.0), IoStatus::kOk);
    EXPECT_EQ(s.read_exact(std::as_writable_bytes(std::span<double>(trial)), 5.0, 5.0), IoStatus::kOk);
    EXPECT_EQ(s.read_exact(std::as_writable_bytes(std::span<double>(request)), 5.0, 5.0), IoStatus::kOk);
    // [daqDisp | daqForce]: a spring of 2000 N/m on each DOF, the floors a little short.
    const std::vector<double> reply{trial[1] - 1e-9, trial[2] - 1e-9, 2000.0 * trial[1], 2000.0 * trial[2]};
    EXPECT_EQ(s.write_all(std::as_bytes(std::span<const double>(reply))), IoStatus::kOk);
    std::vector<double> die(4);
    EXPECT_EQ(s.read_exact(std::as_writable_bytes(std::span<double>(die)), 5.0, 5.0), IoStatus::kOk);
    return die[0];
  });
  AdapterSiteConfig config;
  config.site_id = 2;
  config.port = listener.port();
  config.dofs = 2;
  AdapterLink link(config);
  transport::CommandSample command;
  command.step = 7;
  command.time_s = 0.5;
  command.displacement_m[0] = 0.01;
  command.displacement_m[1] = -0.02;
  ASSERT_EQ(link.send(command), transport::LinkStatus::kOk);
  transport::FeedbackSample feedback;
  ASSERT_EQ(link.receive(feedback), transport::LinkStatus::kOk);
  link.end_run();
  EXPECT_EQ(adapter.get(), kDie);
  EXPECT_EQ(sizes, adapter_sizes(2).to_wire());
  EXPECT_EQ(trial, (std::vector<double>{kSetTrialResponse, 0.01, -0.02, 0.0}));
  EXPECT_EQ(request[0], kGetForce);
  EXPECT_EQ(feedback.step, 7);
  EXPECT_EQ(feedback.site_id, 2u);
  EXPECT_DOUBLE_EQ(feedback.force_n[0], 20.0);
  EXPECT_DOUBLE_EQ(feedback.force_n[1], -40.0);
  EXPECT_NEAR(feedback.displacement_m[1], -0.02, 1e-8);
}

TEST(AdapterLink, AnAdapterThatLeavesIsALostPeerWithItsAddress) {
  TcpListener listener("127.0.0.1", 0);
  auto adapter = std::async(std::launch::async, [&] {
    TcpStream s = *listener.accept(5.0);
    std::array<std::int32_t, 11> sizes{};
    (void)s.read_exact(std::as_writable_bytes(std::span<std::int32_t>(sizes)), 5.0, 5.0);
  });
  AdapterSiteConfig config;
  config.port = listener.port();
  AdapterLink link(config);
  adapter.get();  // the adapter closes its end
  transport::CommandSample command;
  (void)link.send(command);
  transport::FeedbackSample feedback;
  EXPECT_EQ(link.receive(feedback), transport::LinkStatus::kPeerLost);
  EXPECT_THAT(link.failure(), testing::HasSubstr("the OpenSees adapter at 127.0.0.1:"));
}

// An adapter element takes trial displacements only: a command with a channel in force control
// is refused and named, nothing is written (the adapter reads no trial after its sizes).
TEST(AdapterLink, AForceCommandIsRefusedNotDropped) {
  TcpListener listener("127.0.0.1", 0);
  auto adapter = std::async(std::launch::async, [&] {
    TcpStream s = *listener.accept(5.0);
    std::array<std::int32_t, 11> sizes{};
    EXPECT_EQ(s.read_exact(std::as_writable_bytes(std::span<std::int32_t>(sizes)), 5.0, 5.0), IoStatus::kOk);
    std::array<double, 3> trial{};
    return s.read_exact(std::as_writable_bytes(std::span<double>(trial)), 0.5, 0.5);
  });
  AdapterSiteConfig config;
  config.port = listener.port();
  config.dofs = 2;
  AdapterLink link(config);
  transport::CommandSample command;
  command.control_mode[1] = transport::kForceControl;
  command.force_n[1] = 1000.0;
  EXPECT_EQ(link.send(command), transport::LinkStatus::kRefused);
  EXPECT_THAT(link.failure(), testing::HasSubstr("DOF 1 was sent a force command"));
  EXPECT_NE(adapter.get(), IoStatus::kOk);  // no trial reached the adapter
}

TEST(AdapterLink, NoAdapterListeningIsNamedAfterTheTimeout) {
  AdapterSiteConfig config;
  config.port = [] {
    TcpListener probe("127.0.0.1", 0);
    return probe.port();  // free once the probe closes
  }();
  config.connect_timeout_s = 0.2;
  EXPECT_THAT([&] { AdapterLink link(config); },
              testing::ThrowsMessage<std::runtime_error>(testing::HasSubstr("no OpenSees answered at 127.0.0.1:")));
}

}  // namespace
}  // namespace rpsd::opensees
