#include "rpsd/node/udp_controller_actuator.h"

#include "rpsd/node/hardware_link_checks.h"
#include "rpsd/node/owned_actuator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rpsd::node {

using udp_protocol::ControllerCommand;
using udp_protocol::ControllerReply;
using udp_protocol::ControllerStatus;
using udp_protocol::PacketStatus;

void UdpControllerParameters::validate() const {
  check_link_channels(channels);
  Ipv4Endpoint::parse(controller_host, controller_port, "controller_host");
  Ipv4Endpoint::parse(local_host, local_port, "local_host");
  if (controller_port == 0) throw std::invalid_argument("controller_port: required (1-65535)");
  check_link_timing(reply_timeout_s, max_missed_replies, start_timeout_s, start_tolerance_m);
  if (protocol_version == udp_protocol::kVersion1) {
    if (!key.empty()) throw std::invalid_argument("key_file: protocol version 1 authenticates nothing");
  } else if (protocol_version == udp_protocol::kVersion2) {
    if (key.size() < kUdpMinKeyBytes || key.size() > kUdpMaxKeyBytes) {
      throw std::invalid_argument("key_file: protocol version 2 needs a key of " + std::to_string(kUdpMinKeyBytes) +
                                  " to " + std::to_string(kUdpMaxKeyBytes) + " bytes shared with the controller");
    }
  } else {
    throw std::invalid_argument("protocol_version: 1 or 2, got " + std::to_string(protocol_version));
  }
}

namespace {
Ipv4Endpoint validated_local(const UdpControllerParameters& config) {
  config.validate();
  return Ipv4Endpoint::parse(config.local_host, config.local_port, "local_host");
}

constexpr std::array<std::byte, udp_protocol::kNonceBytes> kNoNonce{};
}  // namespace

UdpControllerActuator::UdpControllerActuator(const UdpControllerParameters& config)
    : config_(config),
      controller_(Ipv4Endpoint::parse(config.controller_host, config.controller_port, "controller_host")),
      socket_(validated_local(config)),
      key_(config.protocol_version == udp_protocol::kVersion2 ? std::make_unique<UdpAuthenticator>(config.key)
                                                              : nullptr) {
  config_.key.clear();  // the keyed states are all that is kept
}

bool UdpControllerActuator::encode(const ControllerCommand& command) noexcept {
  if (key_) return udp_protocol::encode_command(command, session_, *key_, command_packet_v2_) == PacketStatus::kOk;
  return udp_protocol::encode_command(command, command_packet_) == PacketStatus::kOk;
}

bool UdpControllerActuator::decode(std::span<const std::byte> bytes, ControllerReply& reply) noexcept {
  if (!key_) return udp_protocol::decode_reply(bytes, reply) == PacketStatus::kOk;
  const PacketStatus s = udp_protocol::decode_reply(bytes, *key_, reply, reply_session_);
  if (s == PacketStatus::kBadTag) {
    ++counters_.unauthenticated_replies;
    return false;
  }
  if (s != PacketStatus::kOk) {
    ++counters_.bad_replies;
    return false;
  }
  // The node's nonce is new at every start(); the controller's is known once the hello is answered.
  const bool ours = reply_session_.node_nonce == session_.node_nonce &&
                    (awaiting_hello_ ? reply_session_.controller_nonce != kNoNonce
                                     : reply_session_.controller_nonce == session_.controller_nonce);
  if (!ours) ++counters_.other_session_replies;
  return ours;
}

bool UdpControllerActuator::send_packet() noexcept {
  const std::span<const std::byte> packet =
      key_ ? std::span<const std::byte>(command_packet_v2_) : std::span<const std::byte>(command_packet_);
  if (!socket_.send_to(packet, controller_)) {
    ++counters_.send_errors;
    return false;
  }
  ++counters_.commands_sent;
  return true;
}

bool UdpControllerActuator::take_queued(std::uint64_t sequence, ControllerReply& reply) noexcept {
  for (;;) {
    Ipv4Endpoint from;
    const long size = socket_.receive(receive_buffer_, from);
    if (size == UdpSocket::kNothingQueued) return false;
    if (size == UdpSocket::kReceiveError) {
      ++counters_.receive_errors;
      return false;
    }
    if (!(from == controller_)) {
      ++counters_.foreign_datagrams;
      continue;
    }
    const auto bytes = std::span<const std::byte>(
        receive_buffer_.data(), std::min<std::size_t>(static_cast<std::size_t>(size), receive_buffer_.size()));
    ControllerReply decoded;
    if (!decode(bytes, decoded)) {
      if (!key_) ++counters_.bad_replies;  // version 2 counted by reason in decode()
    } else if (decoded.sequence == sequence) {
      reply = decoded;
      return true;
    } else if (decoded.sequence < sequence) {
      ++counters_.stale_replies;
    } else {
      ++counters_.bad_replies;  // answers a command never sent
    }
  }
}

bool UdpControllerActuator::await(std::uint64_t sequence, double deadline_s, ControllerReply& reply) noexcept {
  for (;;) {
    if (take_queued(sequence, reply)) return true;
    const double remaining_s = deadline_s - monotonic_seconds();
    if (remaining_s <= 0.0) return false;
    if (socket_.wait_readable(remaining_s) == UdpSocket::Wait::kError) {
      ++counters_.receive_errors;
      return false;
    }
  }
}

void UdpControllerActuator::start(std::span<const double> initial_displacement_m) {
  const int channels = config_.channels;
  if (static_cast<int>(initial_displacement_m.size()) != channels) {
    throw std::invalid_argument("UdpControllerActuator::start: " + std::to_string(channels) +
                                " initial displacements expected, got " +
                                std::to_string(initial_displacement_m.size()));
  }
  // Version 2: a new session, of a nonce no earlier datagram carries; version 1: a query.
  ControllerCommand query;
  query.channels = static_cast<std::uint8_t>(channels);
  query.query = !key_;
  query.hello = key_ != nullptr;
  std::copy(initial_displacement_m.begin(), initial_displacement_m.end(), query.displacement_m.begin());
  if (key_) {
    session_ = {};
    random_nonce(session_.node_nonce);
    awaiting_hello_ = true;
  }
  ControllerReply reply;
  bool answered = false;
  const double give_up_s = monotonic_seconds() + config_.start_timeout_s;
  // A lost datagram is likely enough on a busy network: ask again every 100 ms.
  while (!answered && monotonic_seconds() < give_up_s) {
    query.sequence = ++sequence_;
    if (!encode(query)) throw std::invalid_argument("UdpControllerActuator::start: initial displacement is not finite");
    take_queued(query.sequence, reply);  // drop whatever an earlier session left queued
    send_packet();
    answered = await(query.sequence, std::min(give_up_s, monotonic_seconds() + 0.1), reply);
  }
  awaiting_hello_ = false;
  if (answered && key_) session_.controller_nonce = reply_session_.controller_nonce;
  const std::string who = "UdpControllerActuator: controller at " + controller_.to_string();
  if (!answered) {
    std::ostringstream message;
    message << who << " did not answer within " << config_.start_timeout_s << " s";
    throw std::runtime_error(message.str());
  }
  if (reply.channels != channels) {
    throw std::runtime_error(who + " has " + std::to_string(reply.channels) + " channels, the config " +
                             std::to_string(channels));
  }
  if (reply.status != ControllerStatus::kOk) throw std::runtime_error(who + " reports a fault");
  for (int c = 0; c < channels; ++c) {
    if (std::abs(reply.displacement_m[c] - initial_displacement_m[c]) > config_.start_tolerance_m) {
      std::ostringstream message;
      message << who << ": channel " << c << " measures " << reply.displacement_m[c]
              << " m, the initial displacement is " << initial_displacement_m[c] << " m (start_tolerance_m "
              << config_.start_tolerance_m << ")";
      throw std::runtime_error(message.str());
    }
  }
  consecutive_missed_ = 0;
  link_fault_ = false;
  fault_text_ = {};
}

servo::ActuatorStatus UdpControllerActuator::exchange(std::span<const double> command_m, double period_s,
                                                      servo::ActuatorReading& reading) {
  reading.fresh = false;
  if (link_fault_) return servo::ActuatorStatus::kFault;
  const int channels = config_.channels;
  if (static_cast<int>(command_m.size()) != channels) return servo::ActuatorStatus::kFault;
  ControllerCommand command;
  command.sequence = ++sequence_;
  command.channels = static_cast<std::uint8_t>(channels);
  command.period_s = period_s;
  std::copy(command_m.begin(), command_m.end(), command.displacement_m.begin());
  if (!encode(command)) return servo::ActuatorStatus::kFault;

  ControllerReply reply;
  take_queued(command.sequence, reply);  // stale replies of earlier periods
  const double deadline_s = monotonic_seconds() + period_s + config_.reply_timeout_s;
  const bool answered = send_packet() && await(command.sequence, deadline_s, reply);
  if (answered && reply.channels != channels) {
    ++counters_.bad_replies;
    fault_text_ = "the controller answered for another channel count";
    return servo::ActuatorStatus::kFault;
  }
  if (!answered) {
    ++counters_.missed_replies;
    if (++consecutive_missed_ > config_.max_missed_replies) {
      link_fault_ = true;
      fault_text_ = "the UDP controller stopped answering (more than max_missed_replies periods in a row)";
      return servo::ActuatorStatus::kFault;
    }
    return servo::ActuatorStatus::kNoReply;
  }
  ++counters_.replies;
  consecutive_missed_ = 0;
  for (int c = 0; c < channels; ++c) {
    reading.displacement_m[c] = reply.displacement_m[c];
    reading.force_n[c] = reply.force_n[c];
  }
  reading.fresh = true;
  if (reply.status != ControllerStatus::kOk) {
    ++counters_.controller_faults;
    fault_text_ = "the UDP controller reports a fault";
    return servo::ActuatorStatus::kFault;
  }
  return servo::ActuatorStatus::kOk;
}

UdpControllerParameters UdpControllerParameters::read(config::Source& section, int channels) {
  UdpControllerParameters u;
  u.channels = channels;
  u.controller_host = section.text("host", "the controller's address (dotted IPv4)");
  u.controller_port = static_cast<std::uint16_t>(section.whole_number("port", 1, 65535, "the controller's UDP port"));
  u.local_host = section.optional_text("local_host", "address to bind (dotted IPv4)").value_or(u.local_host);
  u.local_port =
      static_cast<std::uint16_t>(section.whole_number_or("local_port", 0, 65535, 0, "port to bind (0: any free one)"));
  u.reply_timeout_s = section.number_or("reply_timeout_s", u.reply_timeout_s,
                                        {"s", "how long past the control period to wait for a reply", 0.0, 1.0, true});
  u.max_missed_replies = static_cast<int>(section.whole_number_or(
      "max_missed_replies", 0, 1000, u.max_missed_replies, "consecutive missing replies before the actuator faults"));
  u.protocol_version = static_cast<int>(section.whole_number_or("protocol_version", 1, 2, udp_protocol::kVersion2,
                                                                "2: every datagram authenticated; 1: none (legacy)"));
  const auto key_file =
      section.optional_relative_file("key_file", "version 2: the key shared with the controller (mode 0600)");
  // Hardware: nothing in the file can say what the rig can do unless the file says it.
  // optional_section, not section: the error names what to give (a listing descends either way).
  const auto rig = section.optional_section("rig", "what the rig behind the controller can do (required)");
  if (!rig) {
    section.fail("rig", "a hardware node must state its rig's envelope: rig: {stroke_m, force_n, velocity_m_per_s}");
  }
  u.rig = servo::Envelope::read(*rig);
  // Checked once every key is read, so that a listing of the keys sees them all.
  if (u.protocol_version == udp_protocol::kVersion1 && key_file) {
    section.fail("key_file", "protocol version 1 authenticates nothing: remove key_file, or use protocol_version 2");
  }
  if (u.protocol_version == udp_protocol::kVersion2) {
    if (!key_file) {
      section.fail("key_file",
                   "protocol version 2 (the default) needs the key shared with the controller "
                   "(docs/udp-controller-protocol.md); protocol_version: 1 for an unauthenticated legacy link");
    }
    try {
      u.key = read_udp_key_file(*key_file);
    } catch (const std::invalid_argument& e) {
      section.fail("key_file", e.what());
    }
    u.key_file = key_file->string();
  }
  return u;
}

std::string describe_link(const UdpControllerParameters& config) {
  const std::string controller = config.controller_host + ":" + std::to_string(config.controller_port);
  if (config.protocol_version == udp_protocol::kVersion1) {
    return "UDP controller " + controller +
           ", protocol version 1: WARNING: the link is unauthenticated; whoever can send from the controller's address "
           "feeds this node measurements (protocol_version 2 and a key_file authenticate it)";
  }
  return "UDP controller " + controller + ", protocol version 2 (HMAC-SHA-256, key " + config.key_file + ")";
}

OwnedActuator UdpControllerParameters::make(const UdpControllerParameters& config, int) {
  OwnedActuator owned;
  owned.actuator = std::make_unique<UdpControllerActuator>(config);
  return owned;
}

}  // namespace rpsd::node

namespace rpsd::node {

std::string UdpControllerActuator::describe_link() const { return node::describe_link(config_); }

nlohmann::json UdpControllerActuator::link_summary() const {
  const UdpControllerCounters& u = counters_;
  return {{"protocol_version", config_.protocol_version},
          {"commands_sent", u.commands_sent},
          {"replies", u.replies},
          {"missed_replies", u.missed_replies},
          {"stale_replies", u.stale_replies},
          {"bad_replies", u.bad_replies},
          {"foreign_datagrams", u.foreign_datagrams},
          {"unauthenticated_replies", u.unauthenticated_replies},
          {"other_session_replies", u.other_session_replies},
          {"controller_faults", u.controller_faults}};
}

}  // namespace rpsd::node
