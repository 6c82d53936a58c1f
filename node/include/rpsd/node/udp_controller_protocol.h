// The binary protocol between the servo node and an external real-time controller (a
// Speedgoat/xPC target, a LabVIEW loop) over UDP: one fixed-size command datagram per
// control period and one fixed-size reply echoing its sequence number. Little-endian
// whatever the host; doubles are IEEE 754 binary64. Version 1 is unauthenticated; version 2
// appends the session's nonces and an HMAC-SHA-256 tag to every datagram.
// docs/udp-controller-protocol.md is the specification (byte offsets, semantics, timing).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "rpsd/node/udp_authenticator.h"
#include "rpsd/transport/messages.h"

namespace rpsd::node::udp_protocol {

inline constexpr std::uint32_t kCommandMagic = 0x43535052;  // bytes "RPSC" on the wire
inline constexpr std::uint32_t kReplyMagic = 0x52535052;    // bytes "RPSR" on the wire
inline constexpr std::uint16_t kVersion1 = 1;               // unauthenticated: only for a file that asks for it
inline constexpr std::uint16_t kVersion2 = 2;               // each datagram carries its session and an HMAC-SHA-256 tag
inline constexpr int kMaxChannels = transport::kMaxChannels;           // slots in every packet
inline constexpr std::size_t kCommandBytes = 24 + 8 * kMaxChannels;    // 88
inline constexpr std::size_t kReplyBytes = 16 + 2 * 8 * kMaxChannels;  // 144
inline constexpr double kMinPeriodS = 1e-6;                            // command periods outside [min, max] are invalid
inline constexpr double kMaxPeriodS = 1.0;

inline constexpr std::size_t kNonceBytes = 16;
inline constexpr std::size_t kSessionBytes = 2 * kNonceBytes;                                 // node's, controller's
inline constexpr std::size_t kCommandBytesV2 = kCommandBytes + kSessionBytes + kUdpTagBytes;  // 152
inline constexpr std::size_t kReplyBytesV2 = kReplyBytes + kSessionBytes + kUdpTagBytes;      // 208

using CommandPacket = std::array<std::byte, kCommandBytes>;  // version 1
using ReplyPacket = std::array<std::byte, kReplyBytes>;
using CommandPacketV2 = std::array<std::byte, kCommandBytesV2>;
using ReplyPacketV2 = std::array<std::byte, kReplyBytesV2>;

// Command flags (byte 7).
inline constexpr std::uint8_t kFlagQuery = 1u << 0;  // report the measurement, apply nothing
// Version 2 only: start a session (the node's nonce; the controller answers with its own).
inline constexpr std::uint8_t kFlagHello = 1u << 1;

// A version 2 session: both nonces travel in every datagram and are covered by its tag, so a
// datagram of one session is refused in any other (docs/udp-controller-protocol.md).
struct Session {
  std::array<std::byte, kNonceBytes> node_nonce{};        // drawn by the node at each start()
  std::array<std::byte, kNonceBytes> controller_nonce{};  // drawn by the controller at each hello; zero in a hello
  bool operator==(const Session&) const = default;
};

// Controller status in a reply (byte 7).
enum class ControllerStatus : std::uint8_t {
  kOk = 0,
  kFault = 1,  // the controller cannot follow commands (interlock, hydraulics off, own limit)
};

struct ControllerCommand {
  std::uint64_t sequence = 0;
  std::uint8_t channels = 0;
  bool query = false;
  bool hello = false;     // version 2 only; not with query
  double period_s = 0.0;  // 0 for a query or a hello; else in [kMinPeriodS, kMaxPeriodS]
  std::array<double, kMaxChannels> displacement_m{};
};

struct ControllerReply {
  std::uint64_t sequence = 0;  // the command's, echoed
  std::uint8_t channels = 0;
  ControllerStatus status = ControllerStatus::kOk;
  std::array<double, kMaxChannels> displacement_m{};
  std::array<double, kMaxChannels> force_n{};
};

enum class PacketStatus : std::uint8_t {
  kOk,
  kWrongSize,
  kWrongMagic,
  kWrongVersion,
  kBadChannels,  // not in 1..kMaxChannels
  kBadFlags,     // unknown flag bits (a hello in version 1, a hello that is also a query)
  kBadPeriod,    // not finite or out of range, or non-zero in a query or a hello
  kNonFinite,    // a used channel slot holds NaN or infinity
  kBadStatus,    // unknown controller status
  kBadTag,       // version 2: the tag is not the key's for these bytes (another key, or altered)
};

const char* packet_status_name(PacketStatus status);

// Encoders check the same rules as the decoders and write nothing unless the packet is
// valid; unused channel slots are written as zero. Decoders accept any bytes: they check
// size, magic, version, channels, flags/status, period and that every used slot is finite,
// write `out` only on kOk, and set unused slots to zero. All real-time safe, noexcept.
PacketStatus encode_command(const ControllerCommand& command, CommandPacket& out) noexcept;
PacketStatus decode_command(std::span<const std::byte> bytes, ControllerCommand& out) noexcept;
PacketStatus encode_reply(const ControllerReply& reply, ReplyPacket& out) noexcept;
PacketStatus decode_reply(std::span<const std::byte> bytes, ControllerReply& out) noexcept;

// Version 2: the same packet with version 2, then the session (node nonce, controller nonce)
// and the HMAC-SHA-256 tag of everything before it. The decoders check size, magic and
// version, then the tag (kBadTag) before anything else, and give the datagram's session in
// `session` for the caller to compare with its own. All real-time safe, noexcept.
PacketStatus encode_command(const ControllerCommand& command, const Session& session, const UdpAuthenticator& key,
                            CommandPacketV2& out) noexcept;
PacketStatus decode_command(std::span<const std::byte> bytes, const UdpAuthenticator& key, ControllerCommand& out,
                            Session& session) noexcept;
PacketStatus encode_reply(const ControllerReply& reply, const Session& session, const UdpAuthenticator& key,
                          ReplyPacketV2& out) noexcept;
PacketStatus decode_reply(std::span<const std::byte> bytes, const UdpAuthenticator& key, ControllerReply& out,
                          Session& session) noexcept;

}  // namespace rpsd::node::udp_protocol
