// The TCP stream under the lab-controller adapters over 127.0.0.1: whole vectors arrive
// whatever the pieces they were sent in, lines are split at their newline with the rest kept,
// every wait ends at its deadline, a closed peer and an overlong line are told apart.
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "rpsd/node/tcp_stream.h"

namespace rpsd::node {
namespace {

const Ipv4Endpoint kLoopback = Ipv4Endpoint::parse("127.0.0.1", 0, "test");

struct Pair {
  TcpListener listener{kLoopback};
  TcpStream client;
  TcpStream server;
  Pair()
      : client(TcpStream::connect(Ipv4Endpoint::parse("127.0.0.1", listener.port(), "test"), kLoopback, 2.0)),
        server(*listener.accept(2.0)) {}
};

std::span<const std::byte> bytes_of(std::string_view text) { return std::as_bytes(std::span(text)); }
double in(double s) { return monotonic_seconds() + s; }

TEST(TcpStream, AVectorSentInPiecesArrivesWhole) {
  Pair p;
  std::array<double, 4> sent{1.5, -2.25, 3e-9, 4e9};
  const auto raw = std::as_bytes(std::span(sent));
  ASSERT_EQ(p.client.send_all(raw.first(5), in(2.0)), TcpStream::Io::kDone);
  ASSERT_EQ(p.client.send_all(raw.subspan(5), in(2.0)), TcpStream::Io::kDone);
  std::array<double, 4> got{};
  ASSERT_EQ(p.server.receive_exact(std::as_writable_bytes(std::span(got)), in(2.0)), TcpStream::Io::kDone);
  EXPECT_EQ(got, sent);
  EXPECT_EQ(p.server.peer().port, p.client.local_port());
}

// A small message is not held back for Nagle's algorithm on either side of a connection.
TEST(TcpStream, BothEndsSendWithoutNaglesDelay) {
  Pair p;
  EXPECT_TRUE(p.client.sends_without_delay());
  EXPECT_TRUE(p.server.sends_without_delay());
}

TEST(TcpStream, LinesAreSplitAtTheirNewlineAndTheRestKept) {
  Pair p;
  ASSERT_EQ(p.client.send_all(bytes_of("OK\t0\tfirst\nOK\t0\tsec"), in(2.0)), TcpStream::Io::kDone);
  std::array<char, 64> line{};
  std::size_t size = 0;
  ASSERT_EQ(p.server.receive_line(line, size, in(2.0)), TcpStream::Io::kDone);
  EXPECT_EQ(std::string_view(line.data(), size), "OK\t0\tfirst\n");
  // The second line is not whole yet: the wait ends at its deadline, then the rest completes it.
  EXPECT_EQ(p.server.receive_line(line, size, in(0.05)), TcpStream::Io::kTimeout);
  ASSERT_EQ(p.client.send_all(bytes_of("ond\n"), in(2.0)), TcpStream::Io::kDone);
  ASSERT_EQ(p.server.receive_line(line, size, in(2.0)), TcpStream::Io::kDone);
  EXPECT_EQ(std::string_view(line.data(), size), "OK\t0\tsecond\n");
}

TEST(TcpStream, AnOverlongLineIsAnOverflowNotALine) {
  Pair p;
  ASSERT_EQ(p.client.send_all(bytes_of("0123456789abcdef\n"), in(2.0)), TcpStream::Io::kDone);
  std::array<char, 8> line{};
  std::size_t size = 0;
  EXPECT_EQ(p.server.receive_line(line, size, in(2.0)), TcpStream::Io::kOverflow);
}

TEST(TcpStream, NothingSentEndsAtTheDeadlineAndAClosedPeerIsSeen) {
  Pair p;
  std::array<std::byte, 16> buffer{};
  EXPECT_EQ(p.server.receive_exact(buffer, in(0.05)), TcpStream::Io::kTimeout);
  EXPECT_FALSE(p.server.readable_now());
  p.client.close();
  EXPECT_EQ(p.server.receive_exact(buffer, in(2.0)), TcpStream::Io::kClosed);
}

TEST(TcpStream, ConnectingToNobodyThrowsNamingThePeer) {
  std::optional<TcpListener> gone(kLoopback);
  const std::uint16_t port = gone->port();
  gone.reset();
  try {
    TcpStream::connect(Ipv4Endpoint::parse("127.0.0.1", port, "test"), kLoopback, 1.0);
    FAIL() << "connected to a closed port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::node
