// The hardware adapter against the controller emulator over 127.0.0.1: the same plants give
// the same measurements bit for bit as in process; missing replies give kNoReply and then a
// latched kFault; stale replies are drained; start() refuses a controller that does not
// answer, has other channels or stands elsewhere; the emulator ignores bad datagrams. Over
// protocol version 2 (the default) unless a test says version 1.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "../servo/paper_rig.h"
#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/udp_controller_actuator.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/servo/transfer_function_plant.h"
#include "udp_test_link.h"

namespace rpsd::node {
namespace {

using testing::adapter_config;
using testing::emulator_config;
using testing::pair;
using testing::Serving;
using udp_protocol::ControllerStatus;

// An emulated controller whose actuator is perfect: it measures its command at the end of
// each period, and the load cell reads 1e5 N/m times that.
struct IdealController {
  servo::PureDelayPlant plant{{0.0, 1e5, 8192.0, {}}};
  std::array<servo::Plant*, 1> plants{&plant};
  ControllerEmulator emulator{plants, emulator_config()};
};

servo::TransferFunctionPlantParameters benchmark() {
  return {{servo::Polynomial{2.18385e13},
           servo::Polynomial{2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13}},
          1.19e6,
          8192.0,
          {}};
}

TEST(UdpControllerActuator, ReproducesTheInProcessActuatorBitForBit) {
  const auto rig = rpsd::testing::paper_rig();
  servo::ServoHydraulicPlant paper_remote(rig), paper_local(rig);
  servo::TransferFunctionPlant tf_remote(benchmark()), tf_local(benchmark());
  servo::Plant* remote[] = {&paper_remote, &tf_remote};
  servo::Plant* local[] = {&paper_local, &tf_local};
  ControllerEmulator emulator(remote, emulator_config());
  servo::SimulatedActuator in_process(local);
  UdpControllerActuator adapter(adapter_config(emulator, 2));
  pair(emulator, adapter);

  const double dt = 1.0 / 1024.0, x0[] = {0.002, -0.001};
  emulator.start(x0);
  in_process.start(x0);
  const Serving serving(emulator);
  adapter.start(x0);
  servo::ActuatorReading over_udp, direct;
  const int periods = 2000;
  for (int i = 1; i <= periods; ++i) {
    const double t = i * dt;
    const double u[] = {0.002 + 0.02 * std::sin(2.0 * std::numbers::pi * 1.5 * t),
                        -0.001 + 0.003 * std::sin(2.0 * std::numbers::pi * 4.0 * t)};
    ASSERT_EQ(adapter.exchange(u, dt, over_udp), servo::ActuatorStatus::kOk) << i;
    ASSERT_EQ(in_process.exchange(u, dt, direct), servo::ActuatorStatus::kOk);
    ASSERT_TRUE(over_udp.fresh);
    for (int c = 0; c < 2; ++c) {
      ASSERT_EQ(over_udp.displacement_m[c], direct.displacement_m[c]) << i << " " << c;
      ASSERT_EQ(over_udp.force_n[c], direct.force_n[c]) << i << " " << c;
    }
  }
  // The paper's actuator at 1.5 Hz, below its 1.96 Hz cut-off, moves by more than half the
  // 20 mm amplitude: the test exchanged real motion, not a standstill.
  EXPECT_GT(std::abs(direct.displacement_m[0] - 0.002), 1e-3);
  EXPECT_EQ(adapter.counters().replies, static_cast<std::uint64_t>(periods) + 0);
  EXPECT_EQ(adapter.counters().commands_sent, static_cast<std::uint64_t>(periods) + 1);  // + the start hello
  EXPECT_EQ(adapter.counters().missed_replies, 0u);
}

TEST(UdpControllerActuator, MissingRepliesGiveNoReplyThenALatchedFault) {
  IdealController ideal;
  auto& [plant, plants, emulator] = ideal;
  UdpControllerParameters config = adapter_config(emulator, 1);
  config.reply_timeout_s = 0.01;
  config.max_missed_replies = 2;
  UdpControllerActuator adapter(config);
  pair(emulator, adapter);
  const double x0[] = {0.001}, u[] = {0.0015};
  emulator.start(x0);
  servo::ActuatorReading reading;
  {
    const Serving serving(emulator);
    adapter.start(x0);
    ASSERT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kOk);
  }
  ASSERT_EQ(reading.displacement_m[0], 0.0015);
  // The controller stops answering.
  EXPECT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kNoReply);
  EXPECT_FALSE(reading.fresh);
  EXPECT_EQ(reading.displacement_m[0], 0.0015);  // the last values are kept
  EXPECT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kNoReply);
  EXPECT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kFault);  // the third in a row: more than 2
  const auto sent = adapter.counters().commands_sent;
  EXPECT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kFault);  // latched, nothing sent
  EXPECT_EQ(adapter.counters().commands_sent, sent);
  EXPECT_EQ(adapter.counters().missed_replies, 3u);

  // Restarting clears the latch once the controller answers again. The three commands it
  // missed are still queued at the emulator and are applied first (in order), then the hello
  // begins a new session.
  const Serving serving(emulator);
  adapter.start(std::span<const double>(u, 1));
  EXPECT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kOk);
  EXPECT_TRUE(reading.fresh);
  // The replies to the three missed commands, of the session start() ended.
  EXPECT_GE(adapter.counters().other_session_replies, 3u);
}

TEST(UdpControllerActuator, StaleRepliesAreDrainedAndCounted) {
  IdealController ideal;
  auto& [plant, plants, emulator] = ideal;
  UdpControllerParameters config = adapter_config(emulator, 1);
  config.reply_timeout_s = 0.01;
  UdpControllerActuator adapter(config);
  pair(emulator, adapter);
  const double x0[] = {0.0};
  emulator.start(x0);
  {
    const Serving serving(emulator);
    adapter.start(x0);
  }
  servo::ActuatorReading reading;
  const double late[] = {0.004}, next[] = {0.005};
  EXPECT_EQ(adapter.exchange(late, 0.001, reading), servo::ActuatorStatus::kNoReply);
  // The controller answers late: its reply waits in the adapter's socket.
  EXPECT_EQ(emulator.serve(2.0), ControllerEmulator::Served::kApplied);
  // A datagram from some other program on the adapter's port.
  UdpSocket stranger(Ipv4Endpoint::parse("127.0.0.1", 0, "test"));
  const std::byte junk[3] = {};
  ASSERT_TRUE(stranger.send_to(junk, Ipv4Endpoint::parse("127.0.0.1", adapter.local_port(), "test")));
  const Serving serving(emulator);
  ASSERT_EQ(adapter.exchange(next, 0.001, reading), servo::ActuatorStatus::kOk);
  EXPECT_EQ(reading.displacement_m[0], 0.005);  // the answer to this command, not the late one
  EXPECT_EQ(adapter.counters().stale_replies, 1u);
  EXPECT_EQ(adapter.counters().foreign_datagrams, 1u);
  EXPECT_EQ(adapter.counters().missed_replies, 1u);
}

TEST(UdpControllerActuator, ControllerFaultIsReportedWithTheMeasurement) {
  IdealController ideal;
  auto& [plant, plants, emulator] = ideal;
  UdpControllerActuator adapter(adapter_config(emulator, 1));
  pair(emulator, adapter);
  const double x0[] = {0.002}, u[] = {0.003};
  emulator.start(x0);
  const Serving serving(emulator);
  adapter.start(x0);
  servo::ActuatorReading reading;
  emulator.set_status(ControllerStatus::kFault);
  EXPECT_EQ(adapter.exchange(u, 0.001, reading), servo::ActuatorStatus::kFault);
  EXPECT_TRUE(reading.fresh);
  EXPECT_EQ(reading.displacement_m[0], 0.002);  // the interlocked controller did not move
  EXPECT_EQ(reading.force_n[0], 1e5 * 0.002);
  emulator.set_status(ControllerStatus::kOk);
  EXPECT_EQ(adapter.exchange(u, 0.001, reading),
            servo::ActuatorStatus::kOk);  // not latched: the controller's own state
  EXPECT_EQ(reading.displacement_m[0], 0.003);
  EXPECT_EQ(adapter.counters().controller_faults, 1u);
}

std::string start_error(UdpControllerActuator& adapter, std::span<const double> x0) {
  try {
    adapter.start(x0);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(UdpControllerActuator, StartRefusesAnAbsentMismatchedOrDisplacedController) {
  IdealController ideal;
  auto& [plant, plants, emulator] = ideal;
  const double zero[] = {0.0}, zeros[] = {0.0, 0.0}, away[] = {0.01};
  emulator.start(zero);

  UdpControllerParameters config = adapter_config(emulator, 1);
  config.start_timeout_s = 0.2;
  UdpControllerActuator silent(config);
  pair(emulator, silent);
  EXPECT_NE(start_error(silent, zero).find("did not answer within 0.2 s"), std::string::npos)
      << start_error(silent, zero);

  const Serving serving(emulator);
  UdpControllerActuator two(adapter_config(emulator, 2));
  pair(emulator, two);
  EXPECT_NE(start_error(two, zeros).find("has 1 channels, the config 2"), std::string::npos);
  UdpControllerActuator one(adapter_config(emulator, 1));
  pair(emulator, one);
  EXPECT_NE(start_error(one, away).find("channel 0 measures 0 m, the initial displacement is 0.01 m"),
            std::string::npos)
      << start_error(one, away);
  EXPECT_THROW(one.start(zeros), std::invalid_argument);
  EXPECT_EQ(start_error(one, zero), "");
}

TEST(UdpControllerActuator, ConfigErrorsNameTheField) {
  const auto message = [](UdpControllerParameters config) -> std::string {
    try {
      config.validate();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  UdpControllerParameters good;
  good.controller_port = 5000;
  good.key = testing::test_key();
  EXPECT_EQ(message(good), "");
  auto bad = good;
  bad.controller_host = "10.0.0";
  EXPECT_EQ(message(bad).rfind("controller_host:", 0), 0u);
  bad = good;
  bad.controller_port = 0;
  EXPECT_EQ(message(bad).rfind("controller_port:", 0), 0u);
  bad = good;
  bad.local_host = "localhost";
  EXPECT_EQ(message(bad).rfind("local_host:", 0), 0u);
  bad = good;
  bad.channels = 9;
  EXPECT_EQ(message(bad).rfind("channels:", 0), 0u);
  bad = good;
  bad.reply_timeout_s = 0.0;
  EXPECT_EQ(message(bad).rfind("reply_timeout_s:", 0), 0u);
  bad = good;
  bad.key.clear();  // version 2, the default, needs a key
  EXPECT_EQ(message(bad).rfind("key_file:", 0), 0u);
  bad.protocol_version = udp_protocol::kVersion1;
  EXPECT_EQ(message(bad), "");
  bad.key = testing::test_key();  // version 1 authenticates nothing: a key would mislead
  EXPECT_EQ(message(bad).rfind("key_file:", 0), 0u);
  bad = good;
  bad.protocol_version = 3;
  EXPECT_EQ(message(bad).rfind("protocol_version:", 0), 0u);
  bad = good;
  bad.max_missed_replies = -1;
  EXPECT_EQ(message(bad).rfind("max_missed_replies:", 0), 0u);
  EXPECT_THROW(UdpControllerActuator{bad}, std::invalid_argument);
}

TEST(ControllerEmulator, IgnoresBadDatagramsAndStops) {
  servo::PureDelayPlant plant{{0.0, 1e5, 8192.0, {}}};
  servo::Plant* plants[] = {&plant};
  ControllerEmulator emulator(plants, emulator_config(udp_protocol::kVersion1));
  const double x0[] = {0.0};
  emulator.start(x0);
  UdpSocket client(Ipv4Endpoint::parse("127.0.0.1", 0, "test"));
  emulator.set_node(testing::loopback(client.local_port()));
  const Ipv4Endpoint to = Ipv4Endpoint::parse("127.0.0.1", emulator.port(), "test");
  using Served = ControllerEmulator::Served;

  const std::byte garbage[5] = {std::byte{1}, std::byte{2}};
  ASSERT_TRUE(client.send_to(garbage, to));
  EXPECT_EQ(emulator.serve(2.0), Served::kIgnored);
  udp_protocol::ControllerCommand command;
  command.channels = 1;
  command.query = true;  // the node begins a session
  command.sequence = 1;
  udp_protocol::CommandPacket packet{};
  ASSERT_EQ(udp_protocol::encode_command(command, packet), udp_protocol::PacketStatus::kOk);
  ASSERT_TRUE(client.send_to(packet, to));
  EXPECT_EQ(emulator.serve(2.0), Served::kQueried);
  command.query = false;
  command.sequence = 5;
  command.channels = 2;
  command.period_s = 0.001;
  ASSERT_EQ(udp_protocol::encode_command(command, packet), udp_protocol::PacketStatus::kOk);
  ASSERT_TRUE(client.send_to(packet, to));
  EXPECT_EQ(emulator.serve(2.0), Served::kIgnored);  // two channels to a one-channel controller
  command.channels = 1;
  command.displacement_m[0] = 0.001;
  ASSERT_EQ(udp_protocol::encode_command(command, packet), udp_protocol::PacketStatus::kOk);
  ASSERT_TRUE(client.send_to(packet, to));
  EXPECT_EQ(emulator.serve(2.0), Served::kApplied);
  ASSERT_TRUE(client.send_to(packet, to));  // the same datagram again (a network duplicate)
  EXPECT_EQ(emulator.serve(2.0), Served::kIgnored);
  EXPECT_EQ(emulator.serve(0.01), Served::kTimeout);
  const auto& counters = emulator.counters();
  EXPECT_EQ(counters.bad_packets, 1u);
  EXPECT_EQ(counters.wrong_channels, 1u);
  EXPECT_EQ(counters.commands_applied, 1u);
  EXPECT_EQ(counters.stale_commands, 1u);
  EXPECT_EQ(plant.time_s(), 0.001);  // only the valid command advanced the plant

  // The only replies the client got are the query's and the valid command's.
  std::array<std::byte, 200> buffer{};
  Ipv4Endpoint from;
  ASSERT_EQ(client.wait_readable(2.0), UdpSocket::Wait::kReadable);
  ASSERT_EQ(client.receive(buffer, from), static_cast<long>(udp_protocol::kReplyBytes));
  ASSERT_EQ(client.wait_readable(2.0), UdpSocket::Wait::kReadable);
  ASSERT_EQ(client.receive(buffer, from), static_cast<long>(udp_protocol::kReplyBytes));
  udp_protocol::ControllerReply reply;
  ASSERT_EQ(udp_protocol::decode_reply(std::span<const std::byte>(buffer.data(), udp_protocol::kReplyBytes), reply),
            udp_protocol::PacketStatus::kOk);
  EXPECT_EQ(reply.sequence, 5u);
  EXPECT_EQ(reply.displacement_m[0], 0.001);
  EXPECT_EQ(client.receive(buffer, from), UdpSocket::kNothingQueued);

  // A stop request ends a long wait at once (no wall-clock assertion: the test would hang).
  std::thread stopper([&] { emulator.request_stop(); });
  EXPECT_EQ(emulator.serve(3600.0), Served::kStopped);
  stopper.join();
}

}  // namespace
}  // namespace rpsd::node
