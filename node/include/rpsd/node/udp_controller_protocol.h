// The binary protocol between the servo node and an external real-time controller (a
// Speedgoat/xPC target, a LabVIEW loop) over UDP: one fixed-size command datagram per
// control period and one fixed-size reply echoing its sequence number. Little-endian
// whatever the host; doubles are IEEE 754 binary64. docs/udp-controller-protocol.md is the
// specification (byte offsets, semantics, timing).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "rpsd/transport/messages.h"

namespace rpsd::node::udp_protocol {

inline constexpr std::uint32_t kCommandMagic = 0x43535052;  // bytes "RPSC" on the wire
inline constexpr std::uint32_t kReplyMagic = 0x52535052;    // bytes "RPSR" on the wire
inline constexpr std::uint16_t kVersion = 1;
inline constexpr int kMaxChannels = transport::kMaxChannels;           // slots in every packet
inline constexpr std::size_t kCommandBytes = 24 + 8 * kMaxChannels;    // 88
inline constexpr std::size_t kReplyBytes = 16 + 2 * 8 * kMaxChannels;  // 144
inline constexpr double kMinPeriodS = 1e-6;                            // command periods outside [min, max] are invalid
inline constexpr double kMaxPeriodS = 1.0;

using CommandPacket = std::array<std::byte, kCommandBytes>;
using ReplyPacket = std::array<std::byte, kReplyBytes>;

// Command flags (byte 7).
inline constexpr std::uint8_t kFlagQuery = 1u << 0;  // report the measurement, apply nothing, start a session

// Controller status in a reply (byte 7).
enum class ControllerStatus : std::uint8_t {
  kOk = 0,
  kFault = 1,  // the controller cannot follow commands (interlock, hydraulics off, own limit)
};

struct ControllerCommand {
  std::uint64_t sequence = 0;
  std::uint8_t channels = 0;
  bool query = false;
  double period_s = 0.0;  // 0 for a query; else in [kMinPeriodS, kMaxPeriodS]
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
  kBadFlags,     // unknown flag bits
  kBadPeriod,    // not finite or out of range, or non-zero in a query
  kNonFinite,    // a used channel slot holds NaN or infinity
  kBadStatus,    // unknown controller status
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

}  // namespace rpsd::node::udp_protocol
