// The server side of a genericClient against a scripted client on loopback: the requests of
// an OpenSees step reach the site in order, and every way a client can break the protocol
// (wrong sizes, a short message, a non-finite value, leaving mid-step, an unknown action)
// ends the session without a trial reaching the actuators, with not-a-number answers.
#include "rpsd/opensees/generic_client_session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <future>
#include <thread>

#include "peer.h"

namespace rpsd::opensees {
namespace {

using test::read_reply;
using test::write_ints;
using test::write_request;

// A spring of k N/m on each basic DOF; counts what reached it.
class SpringSite : public GenericClientSite {
 public:
  bool set_trial(std::span<const double> d, std::span<const double>, std::span<const double>, double t) override {
    ++trials;
    last_d.assign(d.begin(), d.end());
    last_time_s = t;
    return true;
  }
  bool force(std::span<double> f) override {
    ++forces;
    if (stop_at_force) return false;
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = k * (i < last_d.size() ? last_d[i] : 0.0);
    return true;
  }
  void measured_displacement(std::span<double> d) override {
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = i < last_d.size() ? last_d[i] : 0.0;
  }
  void stiffness(std::span<double> m) override {
    const std::size_t n = static_cast<std::size_t>(std::sqrt(static_cast<double>(m.size())));
    for (std::size_t i = 0; i < n; ++i) m[i * n + i] = k;
  }
  void commit() override { ++commits; }

  double k = 1000.0;
  bool stop_at_force = false;
  int trials = 0, forces = 0, commits = 0;
  std::vector<double> last_d;
  double last_time_s = -1.0;
};

// Runs the session of a `dofs`-DOF site in a thread while `client` scripts the peer.
template <class Client>
SessionEnd serve_with(SpringSite& site, int dofs, Client client, std::int64_t* drained = nullptr) {
  TcpListener listener("127.0.0.1", 0);
  auto served = std::async(std::launch::async, [&] {
    auto stream = listener.accept(5.0);
    SessionOptions options;
    options.basic_dofs = dofs;
    options.idle_timeout_s = 3.0;
    options.message_timeout_s = 0.5;
    GenericClientSession session(std::move(*stream), options);
    const SessionEnd end = session.serve(site);
    if (drained) *drained = session.drained();
    return end;
  });
  TcpStream peer = TcpStream::connect("127.0.0.1", listener.port(), 5.0);
  client(peer);
  peer.close();
  return served.get();
}

TEST(GenericClientSession, AStepOfAnExplicitSchemeReachesTheSiteAndItsForcesGoBack) {
  SpringSite site;
  std::vector<double> force, stiffness;
  const SessionEnd end = serve_with(site, 1, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    write_request(c, 256, {kGetMass});
    EXPECT_EQ(read_reply(c, 256)[0], 0.0);  // no mass apart from the measured force
    write_request(c, 256, {kSetTrialResponse, 0.002, 0.1, 0.0, 0.0009765625});
    write_request(c, 256, {kGetForce});
    force = read_reply(c, 256);
    write_request(c, 256, {kGetInitialStiff});
    stiffness = read_reply(c, 256);
    write_request(c, 256, {kCommitState});
    write_request(c, 256, {kDie});
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kDie);
  EXPECT_EQ(site.trials, 1);
  EXPECT_DOUBLE_EQ(site.last_time_s, 0.0009765625);
  EXPECT_DOUBLE_EQ(force[0], 2.0);  // 1000 N/m x 2 mm
  EXPECT_EQ(force[1], 0.0);         // the rest of the reply is zero
  EXPECT_DOUBLE_EQ(stiffness[0], 1000.0);
  EXPECT_EQ(site.commits, 1);
}

TEST(GenericClientSession, AnElementOfOtherDofsIsRefusedAndAnsweredWithNotANumber) {
  SpringSite site;
  std::vector<double> reply;
  const SessionEnd end = serve_with(site, 1, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(2).to_wire());
    write_request(c, 256, {kSetTrialResponse, 0.001, 0.002});
    write_request(c, 256, {kGetForce});
    reply = read_reply(c, 256);
    write_request(c, 256, {kDie});
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kWrongSizes);
  EXPECT_THAT(end.text, testing::HasSubstr("the element has 2 basic DOFs (ctrlDisp), the site 1"));
  EXPECT_EQ(site.trials, 0);
  EXPECT_TRUE(std::isnan(reply[0]));
}

TEST(GenericClientSession, AShortMessageEndsTheSessionBeforeItReachesTheSite) {
  SpringSite site;
  const SessionEnd end = serve_with(site, 1, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    std::vector<double> half(100, 0.0);
    half[0] = kSetTrialResponse;
    half[1] = 0.003;
    ASSERT_EQ(c.write_all(std::as_bytes(std::span<const double>(half))), IoStatus::kOk);
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kShortMessage);
  EXPECT_EQ(site.trials, 0);
}

TEST(GenericClientSession, ANonFiniteTrialNeverReachesTheSite) {
  SpringSite site;
  std::vector<double> reply;
  const SessionEnd end = serve_with(site, 1, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    write_request(c, 256, {kSetTrialResponse, 0.001, 0.0, 0.0, 0.001});
    write_request(c, 256, {kGetForce});
    (void)read_reply(c, 256);
    write_request(c, 256, {kSetTrialResponse, 0.0, std::numeric_limits<double>::infinity(), 0.0, 0.002});
    write_request(c, 256, {kGetForce});
    reply = read_reply(c, 256);
    write_request(c, 256, {kDie});
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kNonFinite);
  EXPECT_EQ(site.trials, 1);  // the first, finite one only
  EXPECT_EQ(site.forces, 1);
  EXPECT_TRUE(std::isnan(reply[0]));
}

TEST(GenericClientSession, AClientThatLeavesMidStepLeavesItsTrialUnexecuted) {
  SpringSite site;
  const SessionEnd end = serve_with(site, 1, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    write_request(c, 256, {kSetTrialResponse, 0.004, 0.0, 0.0, 0.001});
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kClosed);
  EXPECT_EQ(site.trials, 1);
  EXPECT_EQ(site.forces, 0);  // its force was never asked: the trial was never commanded
}

TEST(GenericClientSession, OnceTheSiteStopsEveryAnswerIsNotANumberUntilTheClientIsDone) {
  SpringSite site;
  site.stop_at_force = true;
  std::vector<double> first, later;
  std::int64_t drained = 0;
  const SessionEnd end = serve_with(
      site, 1,
      [&](TcpStream& c) {
        write_ints(c, generic_client_sizes(1).to_wire());
        write_request(c, 256, {kSetTrialResponse, 0.004, 0.0, 0.0, 0.001});
        write_request(c, 256, {kGetForce});
        first = read_reply(c, 256);
        write_request(c, 256, {kCommitState});
        write_request(c, 256, {kSetTrialResponse, 0.005, 0.0, 0.0, 0.002});
        write_request(c, 256, {kGetForce});
        later = read_reply(c, 256);
        write_request(c, 256, {kDie});
      },
      &drained);
  EXPECT_EQ(end.kind, SessionEnd::Kind::kSiteStopped);
  EXPECT_EQ(site.trials, 1);  // nothing after the stop reached the site
  EXPECT_EQ(site.forces, 1);
  EXPECT_EQ(site.commits, 0);
  EXPECT_TRUE(std::isnan(first[0]));
  EXPECT_TRUE(std::isnan(later[0]));
  EXPECT_EQ(drained, 2);
}

TEST(GenericClientSession, AnActionTheProtocolDoesNotHaveIsNamed) {
  SpringSite site;
  const SessionEnd end = serve_with(site, 1, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    write_request(c, 256, {42.5});
    (void)read_reply(c, 256);
    write_request(c, 256, {kDie});
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kUnknownAction);
  EXPECT_THAT(end.text, testing::HasSubstr("action 42.5"));
}

}  // namespace
}  // namespace rpsd::opensees
