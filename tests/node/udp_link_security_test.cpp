// Who may command an actuator through the UDP controller link (issue 25). Before, any local
// process could: a command with sequence 10^12 and x = 0.2 m and then a query with sequence 0
// from another socket moved the emulated piston to 0.2 m. Now the emulator takes datagrams
// from its node's address and port only; within a session a sequence only moves forward (a
// query resets nothing); and in version 2 every datagram carries its session's nonces under an
// HMAC-SHA-256 tag, so that another key's datagram, or a genuine one of another session, is
// refused on both sides. Real UDP sockets on 127.0.0.1.
#include <gtest/gtest.h>

#include <array>
#include <future>
#include <optional>
#include <span>
#include <vector>

#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/udp_controller_actuator.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "udp_test_link.h"

namespace rpsd::node {
namespace {

using testing::adapter_config;
using testing::emulator_config;
using testing::loopback;
using testing::pair;
using testing::Serving;
using testing::test_key;
using udp_protocol::ControllerCommand;
using udp_protocol::ControllerReply;
using udp_protocol::PacketStatus;
using udp_protocol::Session;
using Served = ControllerEmulator::Served;

// One emulated channel whose piston is where it was commanded at the end of each period.
struct Rig {
  explicit Rig(int version, const std::vector<std::byte>& key = test_key())
      : emulator(plants, emulator_config(version, key)) {
    const double x0[] = {0.0};
    emulator.start(x0);
  }
  double position_m() const { return emulator.reading().displacement_m[0]; }
  servo::PureDelayPlant plant{{0.0, 1e5, 8192.0, {}}};
  std::array<servo::Plant*, 1> plants{&plant};
  ControllerEmulator emulator;
};

// Another process's socket on this host: the two datagrams, version 1 as it reported.
void send_the_reported_datagrams(ControllerEmulator& emulator) {
  UdpSocket stranger(loopback(0));
  ControllerCommand command;
  command.sequence = 1'000'000'000'000ull;
  command.channels = 1;
  command.period_s = 0.001;
  command.displacement_m[0] = 0.2;
  udp_protocol::CommandPacket packet{};
  ASSERT_EQ(udp_protocol::encode_command(command, packet), PacketStatus::kOk);
  ASSERT_TRUE(stranger.send_to(packet, loopback(emulator.port())));
  ControllerCommand query;
  query.sequence = 0;
  query.channels = 1;
  query.query = true;
  ASSERT_EQ(udp_protocol::encode_command(query, packet), PacketStatus::kOk);
  ASSERT_TRUE(stranger.send_to(packet, loopback(emulator.port())));
  EXPECT_EQ(emulator.serve(2.0), Served::kIgnored);
  EXPECT_EQ(emulator.serve(2.0), Served::kIgnored);
}

TEST(UdpLinkSecurity, AStrangersCommandAndQueryDoNotMoveThePiston) {
  for (const int version : {udp_protocol::kVersion1, udp_protocol::kVersion2}) {
    SCOPED_TRACE(version);
    Rig rig(version);
    UdpControllerActuator node(adapter_config(rig.emulator, 1));
    pair(rig.emulator, node);
    const double x0[] = {0.0}, x[] = {0.001}, next[] = {0.002};
    servo::ActuatorReading reading;
    {
      const Serving serving(rig.emulator);
      node.start(x0);
      ASSERT_EQ(node.exchange(x, 0.001, reading), servo::ActuatorStatus::kOk);
    }
    for (int attempt = 0; attempt < 3; ++attempt) send_the_reported_datagrams(rig.emulator);  // the 3 tries
    EXPECT_EQ(rig.position_m(), 0.001);                                                       // not 0.2 m
    EXPECT_EQ(rig.emulator.counters().foreign_datagrams, 6u);
    EXPECT_EQ(rig.emulator.counters().commands_applied, 1u);
    // The node's session goes on: the stranger's query reset nothing and its sequence took nothing.
    const Serving serving(rig.emulator);
    ASSERT_EQ(node.exchange(next, 0.001, reading), servo::ActuatorStatus::kOk);
    EXPECT_EQ(reading.displacement_m[0], 0.002);
    EXPECT_EQ(rig.emulator.counters().sessions, 1u);
  }
}

// Plays the node's side of version 2 with hand-made datagrams, from the address and port the
// emulator takes datagrams from.
class HandMadeNode {
 public:
  HandMadeNode(ControllerEmulator& emulator, const std::vector<std::byte>& key = test_key())
      : emulator_(emulator), key_(key) {
    emulator.set_node(loopback(socket_.local_port()));
  }

  // Begins a session with the node nonce `seed`; returns it as the controller answered.
  Session hello(std::uint64_t sequence, std::uint8_t seed) {
    Session session;
    session.node_nonce.fill(std::byte{seed});
    ControllerCommand hello;
    hello.hello = true;
    hello.channels = 1;
    hello.sequence = sequence;
    udp_protocol::CommandPacketV2 packet{};
    EXPECT_EQ(udp_protocol::encode_command(hello, session, key_, packet), PacketStatus::kOk);
    EXPECT_EQ(send(packet), Served::kQueried);
    return answered(sequence).value_or(Session{});
  }

  udp_protocol::CommandPacketV2 command(std::uint64_t sequence, double x_m, const Session& session,
                                        bool query = false) {
    ControllerCommand command;
    command.sequence = sequence;
    command.channels = 1;
    command.query = query;
    command.period_s = query ? 0.0 : 0.001;
    command.displacement_m[0] = x_m;
    udp_protocol::CommandPacketV2 packet{};
    EXPECT_EQ(udp_protocol::encode_command(command, session, key_, packet), PacketStatus::kOk);
    return packet;
  }

  Served send(std::span<const std::byte> datagram) {
    EXPECT_TRUE(socket_.send_to(datagram, loopback(emulator_.port())));
    return emulator_.serve(2.0);
  }

  // The session of the reply to `sequence`, if one came (older replies are skipped).
  std::optional<Session> answered(std::uint64_t sequence) {
    std::array<std::byte, 300> buffer{};
    Ipv4Endpoint from;
    while (socket_.wait_readable(2.0) == UdpSocket::Wait::kReadable) {
      const long size = socket_.receive(buffer, from);
      ControllerReply reply;
      Session session;
      if (size > 0 &&
          udp_protocol::decode_reply(std::span<const std::byte>(buffer.data(), static_cast<std::size_t>(size)), key_,
                                     reply, session) == PacketStatus::kOk &&
          reply.sequence == sequence) {
        return session;
      }
    }
    return std::nullopt;
  }

 private:
  ControllerEmulator& emulator_;
  UdpAuthenticator key_;
  UdpSocket socket_{loopback(0)};
};

TEST(UdpLinkSecurity, ASequenceOnlyMovesForwardWithinASession) {
  Rig rig(udp_protocol::kVersion2);
  HandMadeNode node(rig.emulator);
  const Session session = node.hello(10, 0xA1);
  ASSERT_NE(session.controller_nonce, Session{}.controller_nonce);  // the controller drew its own
  EXPECT_EQ(node.send(node.command(11, 0.001, session)), Served::kApplied);
  EXPECT_EQ(node.send(node.command(0, 0.0, session, true)),
            Served::kIgnored);  // a query with sequence 0 resets nothing
  EXPECT_EQ(node.send(node.command(11, 0.005, session)), Served::kIgnored);
  EXPECT_EQ(node.send(node.command(5, 0.005, session)), Served::kIgnored);
  EXPECT_EQ(rig.position_m(), 0.001);
  EXPECT_EQ(rig.emulator.counters().stale_commands, 3u);
  EXPECT_EQ(node.send(node.command(12, 0.0, session, true)), Served::kQueried);  // forward: answered
  EXPECT_EQ(node.send(node.command(13, 0.002, session)), Served::kApplied);
  EXPECT_EQ(rig.position_m(), 0.002);
}

TEST(UdpLinkSecurity, ADatagramOfAnotherSessionIsRefused) {
  Rig rig(udp_protocol::kVersion2);
  HandMadeNode node(rig.emulator);
  const Session a = node.hello(1, 0xA);
  const auto a2 = node.command(2, 0.003, a), a3 = node.command(3, 0.004, a);
  EXPECT_EQ(node.send(a2), Served::kApplied);
  EXPECT_EQ(node.send(a3), Served::kApplied);
  const Session b = node.hello(1, 0xB);  // the node restarted: a new session, sequences from 1 again
  ASSERT_NE(b.controller_nonce, a.controller_nonce);
  EXPECT_EQ(node.send(node.command(2, 0.0, b)), Served::kApplied);
  EXPECT_EQ(node.send(a3), Served::kIgnored);  // captured in session a, genuine, sequence forward in b
  EXPECT_EQ(rig.position_m(), 0.0);
  EXPECT_EQ(rig.emulator.counters().other_session, 1u);
  // Replaying a's hello begins a session (nobody can tell it from a restart), but of a new
  // controller nonce: a's commands stay refused. The node's session is over: it faults safe.
  ControllerCommand hello;
  hello.hello = true;
  hello.channels = 1;
  hello.sequence = 1;
  udp_protocol::CommandPacketV2 replayed_hello{};
  const UdpAuthenticator key(test_key());
  Session a_hello;
  a_hello.node_nonce = a.node_nonce;
  ASSERT_EQ(udp_protocol::encode_command(hello, a_hello, key, replayed_hello), PacketStatus::kOk);
  EXPECT_EQ(node.send(replayed_hello), Served::kQueried);
  EXPECT_EQ(node.send(a2), Served::kIgnored);
  EXPECT_EQ(node.send(a3), Served::kIgnored);
  EXPECT_EQ(rig.position_m(), 0.0);
  EXPECT_EQ(rig.emulator.counters().other_session, 3u);
  EXPECT_EQ(rig.emulator.counters().commands_applied, 3u);
}

TEST(UdpLinkSecurity, AnotherKeyIsRefusedAndMovesNothing) {
  Rig rig(udp_protocol::kVersion2, test_key(1));
  UdpControllerParameters config = adapter_config(rig.emulator, 1, test_key(2));
  config.start_timeout_s = 0.3;
  UdpControllerActuator node(config);
  pair(rig.emulator, node);
  const double x0[] = {0.0};
  {
    const Serving serving(rig.emulator);
    EXPECT_THROW(node.start(x0), std::runtime_error);  // no answer: its hellos were refused
  }
  EXPECT_GE(rig.emulator.counters().unauthenticated, 1u);
  EXPECT_EQ(rig.emulator.counters().sessions, 0u);
  // A command tagged with the wrong key, even from the node's port, moves nothing.
  HandMadeNode intruder(rig.emulator, test_key(2));
  EXPECT_EQ(intruder.send(intruder.command(99, 0.2, Session{})), Served::kIgnored);
  EXPECT_EQ(rig.position_m(), 0.0);
  EXPECT_EQ(rig.emulator.counters().commands_applied, 0u);
}

// Plays the controller's side by hand, to send the node replies no emulator would.
class HandMadeController {
 public:
  explicit HandMadeController(const std::vector<std::byte>& key = test_key()) : key_(key) {}
  std::uint16_t port() const { return socket_.local_port(); }

  // The next command from the node, and its session.
  std::pair<ControllerCommand, Session> receive() {
    std::array<std::byte, 300> buffer{};
    ControllerCommand command;
    Session session;
    if (socket_.wait_readable(5.0) == UdpSocket::Wait::kReadable) {
      const long size = socket_.receive(buffer, node_);
      EXPECT_EQ(udp_protocol::decode_command(std::span<const std::byte>(buffer.data(), static_cast<std::size_t>(size)),
                                             key_, command, session),
                PacketStatus::kOk);
    }
    return {command, session};
  }

  void reply(std::uint64_t sequence, double x_m, const Session& session, const UdpAuthenticator& key) {
    ControllerReply reply;
    reply.sequence = sequence;
    reply.channels = 1;
    reply.displacement_m[0] = x_m;
    reply.force_n[0] = 1e5 * x_m;
    udp_protocol::ReplyPacketV2 packet{};
    ASSERT_EQ(udp_protocol::encode_reply(reply, session, key, packet), PacketStatus::kOk);
    ASSERT_TRUE(socket_.send_to(packet, node_));
  }
  void reply(std::uint64_t sequence, double x_m, const Session& session) { reply(sequence, x_m, session, key_); }

 private:
  UdpAuthenticator key_;
  UdpSocket socket_{loopback(0)};
  Ipv4Endpoint node_;
};

TEST(UdpLinkSecurity, TheNodeRefusesRepliesOfAnotherSessionOrKey) {
  HandMadeController controller;
  UdpControllerParameters config;
  config.channels = 1;
  config.controller_port = controller.port();
  config.local_host = "127.0.0.1";
  config.reply_timeout_s = 0.5;
  config.start_timeout_s = 5.0;
  config.key = test_key();
  UdpControllerActuator node(config);
  const double x0[] = {0.0}, x[] = {0.001};

  // Session 1, then session 2: each start() draws a new node nonce.
  Session first, second;
  for (Session* session : {&first, &second}) {
    auto started = std::async(std::launch::async, [&] { node.start(x0); });
    auto [hello, theirs] = controller.receive();
    ASSERT_TRUE(hello.hello);
    *session = theirs;
    session->controller_nonce.fill(std::byte{static_cast<unsigned char>(session == &first ? 1 : 2)});
    controller.reply(hello.sequence, 0.0, *session);
    started.get();
  }
  ASSERT_NE(first.node_nonce, second.node_nonce);

  servo::ActuatorReading reading;
  auto exchanged = std::async(std::launch::async, [&] { return node.exchange(x, 0.001, reading); });
  const auto [command, session] = controller.receive();
  EXPECT_EQ(session, second);
  controller.reply(command.sequence, 0.2, first);                                  // a reply of session 1
  controller.reply(command.sequence, 0.2, second, UdpAuthenticator(test_key(9)));  // another key
  EXPECT_EQ(exchanged.get(), servo::ActuatorStatus::kNoReply);
  EXPECT_FALSE(reading.fresh);

  exchanged = std::async(std::launch::async, [&] { return node.exchange(x, 0.001, reading); });
  const auto [next, next_session] = controller.receive();
  controller.reply(next.sequence, 0.001, next_session);
  EXPECT_EQ(exchanged.get(), servo::ActuatorStatus::kOk);
  EXPECT_EQ(reading.displacement_m[0], 0.001);
  // Counted by reason (by now: a late one is drained before the next command).
  EXPECT_EQ(node.counters().other_session_replies, 1u);
  EXPECT_EQ(node.counters().unauthenticated_replies, 1u);
  EXPECT_EQ(node.counters().replies, 1u);  // the last command's (start() counts none)
}

}  // namespace
}  // namespace rpsd::node
