// libFuzzer target: the UDP controller protocol's decoders, which read datagrams from the
// network. Any input must give a definite status; an accepted packet must be consistent
// (1..8 channels, finite values) and re-encode to a packet that decodes to the same content.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "rpsd/node/udp_controller_protocol.h"

namespace udp = rpsd::node::udp_protocol;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
  udp::ControllerCommand command;
  if (udp::decode_command(bytes, command) == udp::PacketStatus::kOk) {
    if (command.channels < 1 || command.channels > 8) __builtin_trap();
    for (int c = 0; c < command.channels; ++c) {
      if (!std::isfinite(command.displacement_m[c])) __builtin_trap();
    }
    udp::CommandPacket again;
    udp::ControllerCommand back;
    if (udp::encode_command(command, again) != udp::PacketStatus::kOk) __builtin_trap();
    if (udp::decode_command(again, back) != udp::PacketStatus::kOk || back.sequence != command.sequence)
      __builtin_trap();
  }
  udp::ControllerReply reply;
  if (udp::decode_reply(bytes, reply) == udp::PacketStatus::kOk) {
    if (reply.channels < 1 || reply.channels > 8) __builtin_trap();
    for (int c = 0; c < reply.channels; ++c) {
      if (!std::isfinite(reply.displacement_m[c]) || !std::isfinite(reply.force_n[c])) __builtin_trap();
    }
    udp::ReplyPacket again;
    udp::ControllerReply back;
    if (udp::encode_reply(reply, again) != udp::PacketStatus::kOk) __builtin_trap();
    if (udp::decode_reply(again, back) != udp::PacketStatus::kOk || back.sequence != reply.sequence) __builtin_trap();
  }
  return 0;
}
