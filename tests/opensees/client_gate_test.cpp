// Who the genericClient server lets in, on loopback (every 127/8 address is this host's, so a
// client bound to 127.0.0.2 is another peer): a peer the allow-list does not name is closed
// before anything of it is read, a connection that ends before its setup begins no session,
// and a stop ends the wait (inside a stalled setup: GenericClientSession's tests).
#include "rpsd/opensees/client_gate.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <future>

#include "peer.h"

namespace rpsd::opensees {
namespace {

using test::closed_by_server;
using test::write_ints;

// A client connected to 127.0.0.1:port from the loopback address `source`.
TcpStream connect_from(const char* source, std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in from{}, to{};
  from.sin_family = to.sin_family = AF_INET;
  ::inet_pton(AF_INET, source, &from.sin_addr);
  ::inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  to.sin_port = htons(port);
  EXPECT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&from), sizeof from), 0);
  EXPECT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to), 0);
  return TcpStream(fd, {});
}

GateOptions gate(std::vector<std::string> allowed) {
  GateOptions options;
  options.accept_timeout_s = 60.0;  // a hang guard: each test ends by its own events
  options.allowed = PeerAllowList(allowed);
  options.session.message_timeout_s = 5.0;
  return options;
}

TEST(PeerAllowList, LoopbackOnlyUnlessAddressesAreNamed) {
  const PeerAllowList loopback;
  EXPECT_TRUE(loopback.allows(*parse_ipv4("127.0.0.1")));
  EXPECT_TRUE(loopback.allows(*parse_ipv4("127.3.2.1")));
  EXPECT_FALSE(loopback.allows(*parse_ipv4("198.18.0.1")));
  EXPECT_EQ(loopback.text(), "loopback only (127.0.0.0/8)");
  const PeerAllowList named({"198.18.0.1", "198.18.0.5"});
  EXPECT_TRUE(named.allows(*parse_ipv4("198.18.0.5")));
  EXPECT_FALSE(named.allows(*parse_ipv4("198.18.0.3")));
  EXPECT_FALSE(named.allows(*parse_ipv4("127.0.0.1")));  // once named, only those
  EXPECT_EQ(named.text(), "198.18.0.1, 198.18.0.5");
}

TEST(PeerAllowList, AnAddressThatIsNoHostsIsRefused) {
  EXPECT_EQ(client_address_problem("198.18.0.1"), "");
  EXPECT_THAT(client_address_problem("0.0.0.0"), testing::HasSubstr("no host's address"));
  EXPECT_THAT(client_address_problem("255.255.255.255"), testing::HasSubstr("broadcast"));
  EXPECT_THAT(client_address_problem("224.0.0.1"), testing::HasSubstr("multicast"));
  EXPECT_THAT(client_address_problem("localhost"), testing::HasSubstr("is not an IPv4 address"));
  EXPECT_THAT(client_address_problem("198.18.0"), testing::HasSubstr("is not an IPv4 address"));
  EXPECT_THROW(PeerAllowList({"198.18.0.1", "0.0.0.0"}), std::invalid_argument);
}

TEST(ClientGate, APeerTheAllowListDoesNotNameIsClosedBeforeAnythingOfItIsRead) {
  TcpListener listener("127.0.0.1", 0);
  GateReport report;
  std::vector<std::string> notes;
  auto waited = std::async(std::launch::async, [&] {
    return wait_for_client(listener, gate({"127.0.0.2"}), report, [&](const std::string& l) { notes.push_back(l); });
  });
  TcpStream intruder = connect_from("127.0.0.1", listener.port());
  write_ints(intruder, generic_client_sizes(1).to_wire());
  EXPECT_TRUE(closed_by_server(intruder));
  TcpStream client = connect_from("127.0.0.2", listener.port());
  write_ints(client, generic_client_sizes(1).to_wire());
  std::optional<GenericClientSession> session = waited.get();
  ASSERT_TRUE(session);
  EXPECT_THAT(session->peer(), testing::StartsWith("127.0.0.2:"));
  EXPECT_EQ(report.refused, 1);
  ASSERT_EQ(report.refused_peers.size(), 1U);
  EXPECT_THAT(report.refused_peers[0], testing::StartsWith("127.0.0.1:"));
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_THAT(notes[0], testing::HasSubstr("refused a connection from 127.0.0.1:"));
  EXPECT_THAT(notes[0], testing::HasSubstr("not an allowed client (127.0.0.2"));
}

TEST(ClientGate, AConnectionThatEndsBeforeItsSetupBeginsNoSession) {
  TcpListener listener("127.0.0.1", 0);
  GateReport report;
  std::vector<std::string> notes;
  auto waited = std::async(std::launch::async, [&] {
    return wait_for_client(listener, gate({}), report, [&](const std::string& l) { notes.push_back(l); });
  });
  // A port probe (connect, close), then a client that closes after part of its setup.
  TcpStream::connect("127.0.0.1", listener.port(), 5.0).close();
  TcpStream partial = TcpStream::connect("127.0.0.1", listener.port(), 5.0);
  const std::array<std::int32_t, 5> some{1, 1, 1, 0, 1};
  ASSERT_EQ(partial.write_all(std::as_bytes(std::span<const std::int32_t>(some))), IoStatus::kOk);
  partial.close();
  TcpStream client = TcpStream::connect("127.0.0.1", listener.port(), 5.0);
  write_ints(client, generic_client_sizes(1).to_wire());
  std::optional<GenericClientSession> session = waited.get();
  ASSERT_TRUE(session);
  EXPECT_EQ(report.without_setup, 2);
  EXPECT_EQ(report.refused, 0);
  ASSERT_EQ(notes.size(), 2U);
  EXPECT_THAT(notes[0], testing::HasSubstr("ended before a genericClient's setup"));
}

TEST(ClientGate, AStopEndsTheWait) {
  TcpListener listener("127.0.0.1", 0);
  std::atomic<bool> stop{false};
  GateOptions options = gate({});
  options.accept_timeout_s = 600.0;
  options.session.stop.flag = &stop;
  GateReport report;
  auto waited =
      std::async(std::launch::async, [&] { return wait_for_client(listener, options, report, [](const auto&) {}); });
  stop.store(true);
  // A hang guard, not a measurement: without the stop the wait would last its 600 s.
  ASSERT_EQ(waited.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  EXPECT_FALSE(waited.get());
}

}  // namespace
}  // namespace rpsd::opensees
