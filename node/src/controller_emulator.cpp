#include "rpsd/node/controller_emulator.h"

#include <algorithm>

namespace rpsd::node {

using udp_protocol::ControllerCommand;
using udp_protocol::ControllerReply;
using udp_protocol::ControllerStatus;
using udp_protocol::PacketStatus;

ControllerEmulator::ControllerEmulator(std::span<servo::Plant* const> plants, const ControllerEmulatorConfig& config)
    : actuator_(plants), socket_(Ipv4Endpoint::parse(config.bind_host, config.port, "bind_host")) {
  reading_ = actuator_.measure();
}

void ControllerEmulator::start(std::span<const double> initial_displacement_m) {
  actuator_.start(initial_displacement_m);
  reading_ = actuator_.measure();
  last_sequence_ = 0;
}

void ControllerEmulator::reply(std::uint64_t sequence, ControllerStatus status, const Ipv4Endpoint& to) {
  ControllerReply reply;
  reply.sequence = sequence;
  reply.channels = static_cast<std::uint8_t>(actuator_.channels());
  reply.status = status;
  reply.displacement_m = reading_.displacement_m;
  reply.force_n = reading_.force_n;
  // A plant driven unstable can measure infinity; such a reply is invalid and is not sent.
  if (udp_protocol::encode_reply(reply, reply_packet_) != PacketStatus::kOk || !socket_.send_to(reply_packet_, to)) {
    ++counters_.send_errors;
  }
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
  ControllerCommand command;
  const auto bytes = std::span<const std::byte>(
      receive_buffer_.data(), std::min<std::size_t>(static_cast<std::size_t>(size), receive_buffer_.size()));
  if (udp_protocol::decode_command(bytes, command) != PacketStatus::kOk) {
    ++counters_.bad_packets;
    return Served::kIgnored;
  }
  const ControllerStatus status = status_.load();
  if (command.query) {
    // A query starts a session: the sequence numbers of a restarted node count from here.
    ++counters_.queries;
    last_sequence_ = command.sequence;
    reply(command.sequence, status, from);
    return Served::kQueried;
  }
  if (command.channels != actuator_.channels()) {
    ++counters_.wrong_channels;
    return Served::kIgnored;
  }
  if (command.sequence <= last_sequence_) {
    ++counters_.stale_commands;
    return Served::kIgnored;
  }
  last_sequence_ = command.sequence;
  if (status != ControllerStatus::kOk) {
    ++counters_.refused_commands;
    reply(command.sequence, status, from);
    return Served::kQueried;
  }
  const auto displacement =
      std::span<const double>(command.displacement_m.data(), static_cast<std::size_t>(command.channels));
  actuator_.exchange(displacement, command.period_s, reading_);
  ++counters_.commands_applied;
  reply(command.sequence, status, from);
  return Served::kApplied;
}

}  // namespace rpsd::node
