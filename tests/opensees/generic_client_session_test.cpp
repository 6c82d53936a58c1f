// The server side of a genericClient against a scripted client on loopback: the requests of
// an OpenSees step reach the site in order, and every way a client can break the protocol
// (wrong sizes, a short message, a non-finite value, leaving mid-step, an unknown action)
// ends the session without a trial reaching the actuators, with not-a-number answers; and a
// stop request ends it at once whatever the client does (floods, stalls, never reads).
#include "rpsd/opensees/generic_client_session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <thread>

#include "peer.h"

namespace rpsd::opensees {
namespace {

using test::closed_by_server;
using test::read_reply;
using test::try_request;
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
    if (raise_stop && forces == raise_stop_at_force) raise_stop->store(true);  // a signal mid-exchange
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
  std::atomic<bool>* raise_stop = nullptr;  // set at the force request numbered raise_stop_at_force
  int raise_stop_at_force = 0;
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

// The same with the session's options given; `ended` is set once the session has ended.
template <class Client>
SessionEnd serve_with_options(SpringSite& site, SessionOptions options, Client client,
                              std::atomic<bool>* ended = nullptr) {
  TcpListener listener("127.0.0.1", 0);
  auto served = std::async(std::launch::async, [&] {
    auto stream = listener.accept(5.0);
    GenericClientSession session(std::move(*stream), options);
    const SessionEnd end = session.serve(site);
    if (ended) ended->store(true);
    return end;
  });
  TcpStream peer = TcpStream::connect("127.0.0.1", listener.port(), 5.0);
  client(peer);
  peer.close();  // a server still blocked on this client (the old fault) then ends too
  return served.get();
}

// A reply's worth of bytes, read as a client that does not mind the server having gone.
IoStatus try_reply(TcpStream& c) {
  std::vector<double> reply(256);
  return c.read_exact(std::as_writable_bytes(std::span<double>(reply)), 5.0, 5.0);
}

// Waits, reading nothing, until `ended` is set; false after a minute (a hang guard: the
// client then closes, which frees a server blocked on it).
bool ends_without_reading(const std::atomic<bool>& ended) {
  for (int i = 0; i < 6000 && !ended.load(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return ended.load();
}

// Requests that each ask for a reply, sent and never read, until the server takes nothing
// more (it is blocked writing replies nobody reads) or has gone. The requests sent.
int fill_without_reading(TcpStream& c) {
  std::vector<double> request(256, 0.0);
  request[0] = kGetMass;
  int sent = 0;
  while (c.write_all(std::as_bytes(std::span<const double>(request)), 1.0) == IoStatus::kOk) ++sent;
  return sent;
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

TEST(GenericClientSession, AStopIsSeenBetweenTheRequestsOfAClientThatNeverPauses) {
  // The stop arrives while the 50th step is commanded, as SIGINT during an exchange; the client
  // goes on sending steps back to back, and nothing after the 50th reaches the site.
  std::atomic<bool> stop{false};
  SpringSite site;
  site.raise_stop = &stop;
  site.raise_stop_at_force = 50;
  SessionOptions options;
  options.stop.flag = &stop;
  int answered = 0;
  const SessionEnd end = serve_with_options(site, options, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    for (int n = 1; n <= 2000; ++n) {
      if (try_request(c, 256, {kSetTrialResponse, 1e-5 * n, 0.0, 0.0, n * 0.0009765625}) != IoStatus::kOk) break;
      if (try_request(c, 256, {kGetForce}) != IoStatus::kOk || try_reply(c) != IoStatus::kOk) break;
      ++answered;
    }
    (void)try_request(c, 256, {kDie});
  });
  EXPECT_EQ(end.kind, SessionEnd::Kind::kInterrupted);
  EXPECT_EQ(site.forces, 50);
  EXPECT_EQ(site.trials, 50);
  EXPECT_EQ(answered, 50);  // the step under way is answered, then the connection closes
}

TEST(GenericClientSession, AClientStalledInsideARequestCannotHoldTheServerPastAStop) {
  std::atomic<bool> stop{false};
  SpringSite site;
  SessionOptions options;
  options.stop.flag = &stop;
  options.message_timeout_s = 120.0;  // what the stall would otherwise cost
  options.idle_timeout_s = 120.0;
  bool closed = false;
  const SessionEnd end = serve_with_options(site, options, [&](TcpStream& c) {
    write_ints(c, generic_client_sizes(1).to_wire());
    // A whole step first: its reply says the server is past the setup, serving requests.
    write_request(c, 256, {kSetTrialResponse, 0.002, 0.0, 0.0, 0.0009765625});
    write_request(c, 256, {kGetForce});
    (void)read_reply(c, 256);
    std::vector<double> half(100, 0.0);
    half[0] = kSetTrialResponse;
    half[1] = 0.003;
    ASSERT_EQ(c.write_all(std::as_bytes(std::span<const double>(half))), IoStatus::kOk);
    stop.store(true);
    closed = closed_by_server(c);
  });
  EXPECT_TRUE(closed);
  EXPECT_EQ(end.kind, SessionEnd::Kind::kInterrupted);
  EXPECT_EQ(site.trials, 1);  // the whole step's only
}

TEST(GenericClientSession, AClientStalledInsideItsSetupCannotHoldTheServerPastAStop) {
  std::atomic<bool> stop{false};
  SpringSite site;
  SessionOptions options;
  options.stop.flag = &stop;
  options.message_timeout_s = 120.0;
  bool closed = false;
  const SessionEnd end = serve_with_options(site, options, [&](TcpStream& c) {
    const std::array<std::int32_t, 5> some{1, 1, 1, 0, 1};
    ASSERT_EQ(c.write_all(std::as_bytes(std::span<const std::int32_t>(some))), IoStatus::kOk);
    stop.store(true);
    closed = closed_by_server(c);
  });
  EXPECT_TRUE(closed);
  EXPECT_EQ(end.kind, SessionEnd::Kind::kInterrupted);
}

TEST(GenericClientSession, AClientThatNeverReadsItsRepliesCannotHoldTheServerPastAStop) {
  std::atomic<bool> stop{false};
  SpringSite site;
  SessionOptions options;
  options.stop.flag = &stop;
  options.idle_timeout_s = 120.0;
  int sent = 0;
  std::atomic<bool> ended{false};
  bool ended_in_time = false;
  const SessionEnd end = serve_with_options(
      site, options,
      [&](TcpStream& c) {
        write_ints(c, generic_client_sizes(1).to_wire());
        sent = fill_without_reading(c);
        stop.store(true);
        ended_in_time = ends_without_reading(ended);
      },
      &ended);
  EXPECT_GT(sent, 100);  // the sockets filled: the server was blocked writing a reply
  EXPECT_TRUE(ended_in_time);
  EXPECT_EQ(end.kind, SessionEnd::Kind::kInterrupted);
}

TEST(GenericClientSession, AClientThatNeverReadsItsRepliesIsIdleAfterTheIdleTimeout) {
  SpringSite site;
  SessionOptions options;
  options.idle_timeout_s = 1.0;
  std::atomic<bool> ended{false};
  bool ended_in_time = false;
  const SessionEnd end = serve_with_options(
      site, options,
      [&](TcpStream& c) {
        write_ints(c, generic_client_sizes(1).to_wire());
        (void)fill_without_reading(c);
        ended_in_time = ends_without_reading(ended);
      },
      &ended);
  EXPECT_TRUE(ended_in_time);
  EXPECT_EQ(end.kind, SessionEnd::Kind::kIdle);
  EXPECT_THAT(end.text, testing::HasSubstr("took no reply for 1.0"));
}

}  // namespace
}  // namespace rpsd::opensees
