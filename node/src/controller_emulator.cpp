#include "rpsd/node/controller_emulator.h"

#include "rpsd/node/hardware_link_checks.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rpsd::node {

using udp_protocol::ControllerCommand;
using udp_protocol::ControllerReply;
using udp_protocol::ControllerStatus;
using udp_protocol::PacketStatus;

namespace {

std::unique_ptr<UdpAuthenticator> keyed(const ControllerEmulatorConfig& config) {
  if (config.protocol_version == udp_protocol::kVersion1) return nullptr;
  if (config.protocol_version != udp_protocol::kVersion2) {
    throw std::invalid_argument("protocol_version: 1 or 2, got " + std::to_string(config.protocol_version));
  }
  if (config.key.empty())
    throw std::invalid_argument("key_file: protocol version 2 needs the key shared with the node");
  return std::make_unique<UdpAuthenticator>(config.key);
}

}  // namespace

ControllerEmulatorConfig ControllerEmulatorConfig::read(config::Source& u) {
  ControllerEmulatorConfig c;
  c.bind_host = u.optional_text("bind_host", "the address it listens on (default: 127.0.0.1)").value_or(c.bind_host);
  c.port = static_cast<std::uint16_t>(u.whole_number("port", 1, 65535, "the UDP port it listens on"));
  c.node_host = u.text("node_host", "the node's address: the only one it takes datagrams from (dotted IPv4)");
  c.node_port = static_cast<std::uint16_t>(
      u.whole_number("node_port", 1, 65535, "the node's UDP port (its actuator.local_port): the only one it answers"));
  c.protocol_version = static_cast<int>(u.whole_number_or("protocol_version", 1, 2, udp_protocol::kVersion2,
                                                          "2: every datagram authenticated; 1: none (legacy)"));
  const auto key_file = u.optional_relative_file("key_file", "version 2: the key shared with the node (mode 0600)");
  if (key_file) c.key_file = key_file->string();
  u.finish();
  return c;
}

void ControllerEmulatorConfig::check_and_load_key(config::Source& u) {
  check_ipv4_keys(u, {{"bind_host", bind_host}, {"node_host", node_host}});
  if (protocol_version == udp_protocol::kVersion1 && !key_file.empty()) {
    u.fail("key_file", "protocol version 1 authenticates nothing: remove key_file, or use protocol_version 2");
  }
  if (protocol_version == udp_protocol::kVersion2) {
    if (key_file.empty()) u.fail("key_file", "protocol version 2 (the default) needs the key shared with the node");
    try {
      key = read_udp_key_file(key_file);
    } catch (const std::invalid_argument& e) {
      u.fail("key_file", e.what());
    }
  }
}

ControllerEmulator::ControllerEmulator(std::span<servo::Plant* const> plants, const ControllerEmulatorConfig& config)
    : actuator_(plants),
      socket_(Ipv4Endpoint::parse(config.bind_host, config.port, "bind_host")),
      node_(Ipv4Endpoint::parse(config.node_host, config.node_port, "node_host")),
      version_(config.protocol_version),
      key_(keyed(config)) {
  reading_ = actuator_.measure();
}

ControllerEmulator::~ControllerEmulator() = default;

void ControllerEmulator::start(std::span<const double> initial_displacement_m) {
  actuator_.start(initial_displacement_m);
  reading_ = actuator_.measure();
  last_sequence_ = 0;
  in_session_ = false;
}

void ControllerEmulator::reply(std::uint64_t sequence, ControllerStatus status) {
  ControllerReply reply;
  reply.sequence = sequence;
  reply.channels = static_cast<std::uint8_t>(actuator_.channels());
  reply.status = status;
  reply.displacement_m = reading_.displacement_m;
  reply.force_n = reading_.force_n;
  // A plant driven unstable can measure infinity; such a reply is invalid and is not sent.
  bool sent = false;
  if (key_) {
    sent = udp_protocol::encode_reply(reply, session_, *key_, reply_packet_v2_) == PacketStatus::kOk &&
           socket_.send_to(reply_packet_v2_, node_);
  } else {
    sent =
        udp_protocol::encode_reply(reply, reply_packet_) == PacketStatus::kOk && socket_.send_to(reply_packet_, node_);
  }
  if (!sent) ++counters_.send_errors;
}

bool ControllerEmulator::admit(std::span<const std::byte> bytes, const Ipv4Endpoint& from, ControllerCommand& command,
                               Served& handled) {
  handled = Served::kIgnored;
  // Only the node's own address and port: a stranger's datagram is not even decoded.
  if (!(from == node_)) {
    ++counters_.foreign_datagrams;
    return false;
  }
  bool begins_session = false;
  if (key_) {
    udp_protocol::Session session;
    const PacketStatus s = udp_protocol::decode_command(bytes, *key_, command, session);
    if (s == PacketStatus::kBadTag) {
      ++counters_.unauthenticated;
      return false;
    }
    if (s != PacketStatus::kOk ||
        (command.hello && session.controller_nonce != udp_protocol::Session{}.controller_nonce)) {
      ++counters_.bad_packets;
      return false;
    }
    if (command.hello) {
      // A new session: the node's nonce and a fresh one of ours, which no earlier datagram can carry.
      session_.node_nonce = session.node_nonce;
      random_nonce(session_.controller_nonce);
      begins_session = true;
    } else if (!in_session_ || !(session == session_)) {
      ++(in_session_ ? counters_.other_session : counters_.outside_session);
      return false;
    }
  } else {
    if (udp_protocol::decode_command(bytes, command) != PacketStatus::kOk) {
      ++counters_.bad_packets;
      return false;
    }
    begins_session = command.query;  // version 1: the node's query begins a session
  }
  if (begins_session) {
    in_session_ = true;
    last_sequence_ = command.sequence;
    ++counters_.sessions;
    ++counters_.queries;
    reply(command.sequence, status_.load());
    handled = Served::kQueried;
    return false;
  }
  if (!in_session_) {
    ++counters_.outside_session;
    return false;
  }
  // Within a session the sequence only moves forward, queries included.
  if (command.sequence <= last_sequence_) {
    ++counters_.stale_commands;
    return false;
  }
  if (!command.query && command.channels != actuator_.channels()) {
    ++counters_.wrong_channels;
    return false;
  }
  last_sequence_ = command.sequence;
  return true;
}

ControllerEmulator::Served ControllerEmulator::serve(double timeout_s) {
  const double deadline_s = monotonic_seconds() + std::max(0.0, timeout_s);
  Ipv4Endpoint from;
  long size = UdpSocket::kNothingQueued;
  for (;;) {
    if (stop_requested()) return Served::kStopped;
    size = socket_.receive(receive_buffer_, from);
    if (size >= 0) break;
    const double remaining_s = deadline_s - monotonic_seconds();
    if (remaining_s <= 0.0) return Served::kTimeout;
    socket_.wait_readable(std::min(remaining_s, 0.05));  // short slices: a stop request is seen soon
  }
  const auto bytes = std::span<const std::byte>(
      receive_buffer_.data(), std::min<std::size_t>(static_cast<std::size_t>(size), receive_buffer_.size()));
  ControllerCommand command;
  Served handled = Served::kIgnored;
  if (!admit(bytes, from, command, handled)) return handled;
  const ControllerStatus status = status_.load();
  if (command.query) {
    ++counters_.queries;
    reply(command.sequence, status);
    return Served::kQueried;
  }
  if (status != ControllerStatus::kOk) {
    ++counters_.refused_commands;
    reply(command.sequence, status);
    return Served::kQueried;
  }
  const auto displacement =
      std::span<const double>(command.displacement_m.data(), static_cast<std::size_t>(command.channels));
  actuator_.exchange(displacement, command.period_s, reading_);
  ++counters_.commands_applied;
  reply(command.sequence, status);
  return Served::kApplied;
}

}  // namespace rpsd::node
