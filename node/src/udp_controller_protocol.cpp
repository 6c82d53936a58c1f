#include "rpsd/node/udp_controller_protocol.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace rpsd::node::udp_protocol {
namespace {

// Byte offsets (docs/udp-controller-protocol.md).
constexpr std::size_t kMagicAt = 0, kVersionAt = 4, kChannelsAt = 6, kFlagsOrStatusAt = 7, kSequenceAt = 8;
constexpr std::size_t kPeriodAt = 16, kCommandDisplacementAt = 24;
constexpr std::size_t kReplyDisplacementAt = 16, kReplyForceAt = kReplyDisplacementAt + 8 * kMaxChannels;

// Explicit little-endian byte order, independent of the host's.
void store(std::span<std::byte> bytes, std::size_t at, std::uint64_t value, int size) {
  for (int i = 0; i < size; ++i) bytes[at + i] = static_cast<std::byte>((value >> (8 * i)) & 0xFFu);
}
std::uint64_t load(std::span<const std::byte> bytes, std::size_t at, int size) {
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i) value |= static_cast<std::uint64_t>(bytes[at + i]) << (8 * i);
  return value;
}
void store_double(std::span<std::byte> bytes, std::size_t at, double value) {
  store(bytes, at, std::bit_cast<std::uint64_t>(value), 8);
}
double load_double(std::span<const std::byte> bytes, std::size_t at) {
  return std::bit_cast<double>(load(bytes, at, 8));
}

// The 16 bytes both packets start with.
void store_header(std::span<std::byte> bytes, std::uint32_t magic, std::uint16_t version, std::uint8_t channels,
                  std::uint8_t flags_or_status, std::uint64_t sequence) {
  store(bytes, kMagicAt, magic, 4);
  store(bytes, kVersionAt, version, 2);
  store(bytes, kChannelsAt, channels, 1);
  store(bytes, kFlagsOrStatusAt, flags_or_status, 1);
  store(bytes, kSequenceAt, sequence, 8);
}

bool valid_channels(int channels) { return channels >= 1 && channels <= kMaxChannels; }

bool all_finite(const std::array<double, kMaxChannels>& values, int channels) {
  for (int c = 0; c < channels; ++c) {
    if (!std::isfinite(values[c])) return false;
  }
  return true;
}

PacketStatus check_period(bool no_period, double period_s) {
  if (no_period) return period_s == 0.0 ? PacketStatus::kOk : PacketStatus::kBadPeriod;
  return period_s >= kMinPeriodS && period_s <= kMaxPeriodS ? PacketStatus::kOk
                                                            : PacketStatus::kBadPeriod;  // NaN fails both
}

PacketStatus check(const ControllerCommand& command, std::uint16_t version) {
  if (!valid_channels(command.channels)) return PacketStatus::kBadChannels;
  if (command.hello && (version != kVersion2 || command.query)) return PacketStatus::kBadFlags;
  if (const PacketStatus s = check_period(command.query || command.hello, command.period_s); s != PacketStatus::kOk)
    return s;
  if (!all_finite(command.displacement_m, command.channels)) return PacketStatus::kNonFinite;
  return PacketStatus::kOk;
}

PacketStatus check(const ControllerReply& reply) {
  if (!valid_channels(reply.channels)) return PacketStatus::kBadChannels;
  if (reply.status != ControllerStatus::kOk && reply.status != ControllerStatus::kFault)
    return PacketStatus::kBadStatus;
  if (!all_finite(reply.displacement_m, reply.channels) || !all_finite(reply.force_n, reply.channels))
    return PacketStatus::kNonFinite;
  return PacketStatus::kOk;
}

PacketStatus check_header(std::span<const std::byte> bytes, std::size_t size, std::uint32_t magic,
                          std::uint16_t version) {
  if (bytes.size() != size) return PacketStatus::kWrongSize;
  if (load(bytes, kMagicAt, 4) != magic) return PacketStatus::kWrongMagic;
  if (load(bytes, kVersionAt, 2) != version) return PacketStatus::kWrongVersion;
  return PacketStatus::kOk;
}

std::uint8_t command_flags(const ControllerCommand& command) {
  return static_cast<std::uint8_t>((command.query ? kFlagQuery : 0u) | (command.hello ? kFlagHello : 0u));
}

// The version 1 layout of a command (its first kCommandBytes bytes in version 2).
PacketStatus encode_command_body(const ControllerCommand& command, std::uint16_t version, std::span<std::byte> out) {
  if (const PacketStatus s = check(command, version); s != PacketStatus::kOk) return s;
  store_header(out, kCommandMagic, version, command.channels, command_flags(command), command.sequence);
  store_double(out, kPeriodAt, command.period_s);
  for (int c = 0; c < kMaxChannels; ++c) {
    store_double(out, kCommandDisplacementAt + 8 * c, c < command.channels ? command.displacement_m[c] : 0.0);
  }
  return PacketStatus::kOk;
}

// After check_header: the fields of the first kCommandBytes bytes.
PacketStatus decode_command_body(std::span<const std::byte> bytes, std::uint16_t version, ControllerCommand& out) {
  ControllerCommand command;
  command.channels = static_cast<std::uint8_t>(load(bytes, kChannelsAt, 1));
  const auto flags = static_cast<std::uint8_t>(load(bytes, kFlagsOrStatusAt, 1));
  const std::uint8_t known = version == kVersion2 ? (kFlagQuery | kFlagHello) : kFlagQuery;
  if ((flags & ~known) != 0) return PacketStatus::kBadFlags;
  command.query = (flags & kFlagQuery) != 0;
  command.hello = (flags & kFlagHello) != 0;
  command.sequence = load(bytes, kSequenceAt, 8);
  command.period_s = load_double(bytes, kPeriodAt);
  if (valid_channels(command.channels)) {
    for (int c = 0; c < command.channels; ++c)
      command.displacement_m[c] = load_double(bytes, kCommandDisplacementAt + 8 * c);
  }
  if (const PacketStatus s = check(command, version); s != PacketStatus::kOk) return s;
  out = command;
  return PacketStatus::kOk;
}

PacketStatus encode_reply_body(const ControllerReply& reply, std::uint16_t version, std::span<std::byte> out) {
  if (const PacketStatus s = check(reply); s != PacketStatus::kOk) return s;
  store_header(out, kReplyMagic, version, reply.channels, static_cast<std::uint8_t>(reply.status), reply.sequence);
  for (int c = 0; c < kMaxChannels; ++c) {
    const bool used = c < reply.channels;
    store_double(out, kReplyDisplacementAt + 8 * c, used ? reply.displacement_m[c] : 0.0);
    store_double(out, kReplyForceAt + 8 * c, used ? reply.force_n[c] : 0.0);
  }
  return PacketStatus::kOk;
}

PacketStatus decode_reply_body(std::span<const std::byte> bytes, ControllerReply& out) {
  ControllerReply reply;
  reply.channels = static_cast<std::uint8_t>(load(bytes, kChannelsAt, 1));
  const auto status = static_cast<std::uint8_t>(load(bytes, kFlagsOrStatusAt, 1));
  if (status > static_cast<std::uint8_t>(ControllerStatus::kFault)) return PacketStatus::kBadStatus;
  reply.status = static_cast<ControllerStatus>(status);
  reply.sequence = load(bytes, kSequenceAt, 8);
  if (valid_channels(reply.channels)) {
    for (int c = 0; c < reply.channels; ++c) {
      reply.displacement_m[c] = load_double(bytes, kReplyDisplacementAt + 8 * c);
      reply.force_n[c] = load_double(bytes, kReplyForceAt + 8 * c);
    }
  }
  if (const PacketStatus s = check(reply); s != PacketStatus::kOk) return s;
  out = reply;
  return PacketStatus::kOk;
}

// Version 2's trailer: the session after the body, then the tag of all that precedes it.
void seal(std::span<std::byte> packet, std::size_t body_bytes, const Session& session, const UdpAuthenticator& key) {
  std::copy(session.node_nonce.begin(), session.node_nonce.end(), packet.begin() + body_bytes);
  std::copy(session.controller_nonce.begin(), session.controller_nonce.end(),
            packet.begin() + body_bytes + kNonceBytes);
  const std::size_t signed_bytes = body_bytes + kSessionBytes;
  key.tag(packet.first(signed_bytes), packet.subspan(signed_bytes).first<kUdpTagBytes>());
}

// Checks the tag of a version 2 datagram of the right size and gives its session.
bool open_sealed(std::span<const std::byte> bytes, std::size_t body_bytes, const UdpAuthenticator& key,
                 Session& session) {
  const std::size_t signed_bytes = body_bytes + kSessionBytes;
  if (!key.verify(bytes.first(signed_bytes), bytes.subspan(signed_bytes).first<kUdpTagBytes>())) return false;
  std::copy_n(bytes.begin() + body_bytes, kNonceBytes, session.node_nonce.begin());
  std::copy_n(bytes.begin() + body_bytes + kNonceBytes, kNonceBytes, session.controller_nonce.begin());
  return true;
}

}  // namespace

const char* packet_status_name(PacketStatus status) {
  switch (status) {
    case PacketStatus::kOk:
      return "ok";
    case PacketStatus::kWrongSize:
      return "wrong size";
    case PacketStatus::kWrongMagic:
      return "wrong magic";
    case PacketStatus::kWrongVersion:
      return "wrong version";
    case PacketStatus::kBadChannels:
      return "bad channel count";
    case PacketStatus::kBadFlags:
      return "unknown flags";
    case PacketStatus::kBadPeriod:
      return "bad period";
    case PacketStatus::kNonFinite:
      return "non-finite value";
    case PacketStatus::kBadStatus:
      return "unknown controller status";
    case PacketStatus::kBadTag:
      return "bad authentication tag";
  }
  return "unknown";
}

PacketStatus encode_command(const ControllerCommand& command, CommandPacket& out) noexcept {
  return encode_command_body(command, kVersion1, out);
}

PacketStatus decode_command(std::span<const std::byte> bytes, ControllerCommand& out) noexcept {
  if (const PacketStatus s = check_header(bytes, kCommandBytes, kCommandMagic, kVersion1); s != PacketStatus::kOk)
    return s;
  return decode_command_body(bytes, kVersion1, out);
}

PacketStatus encode_reply(const ControllerReply& reply, ReplyPacket& out) noexcept {
  return encode_reply_body(reply, kVersion1, out);
}

PacketStatus decode_reply(std::span<const std::byte> bytes, ControllerReply& out) noexcept {
  if (const PacketStatus s = check_header(bytes, kReplyBytes, kReplyMagic, kVersion1); s != PacketStatus::kOk) return s;
  return decode_reply_body(bytes, out);
}

PacketStatus encode_command(const ControllerCommand& command, const Session& session, const UdpAuthenticator& key,
                            CommandPacketV2& out) noexcept {
  CommandPacketV2 packet{};
  if (const PacketStatus s = encode_command_body(command, kVersion2, packet); s != PacketStatus::kOk) return s;
  seal(packet, kCommandBytes, session, key);
  out = packet;
  return PacketStatus::kOk;
}

PacketStatus decode_command(std::span<const std::byte> bytes, const UdpAuthenticator& key, ControllerCommand& out,
                            Session& session) noexcept {
  if (const PacketStatus s = check_header(bytes, kCommandBytesV2, kCommandMagic, kVersion2); s != PacketStatus::kOk)
    return s;
  Session found;
  if (!open_sealed(bytes, kCommandBytes, key, found)) return PacketStatus::kBadTag;
  const PacketStatus s = decode_command_body(bytes, kVersion2, out);
  if (s == PacketStatus::kOk) session = found;
  return s;
}

PacketStatus encode_reply(const ControllerReply& reply, const Session& session, const UdpAuthenticator& key,
                          ReplyPacketV2& out) noexcept {
  ReplyPacketV2 packet{};
  if (const PacketStatus s = encode_reply_body(reply, kVersion2, packet); s != PacketStatus::kOk) return s;
  seal(packet, kReplyBytes, session, key);
  out = packet;
  return PacketStatus::kOk;
}

PacketStatus decode_reply(std::span<const std::byte> bytes, const UdpAuthenticator& key, ControllerReply& out,
                          Session& session) noexcept {
  if (const PacketStatus s = check_header(bytes, kReplyBytesV2, kReplyMagic, kVersion2); s != PacketStatus::kOk)
    return s;
  Session found;
  if (!open_sealed(bytes, kReplyBytes, key, found)) return PacketStatus::kBadTag;
  const PacketStatus s = decode_reply_body(bytes, out);
  if (s == PacketStatus::kOk) session = found;
  return s;
}

}  // namespace rpsd::node::udp_protocol
