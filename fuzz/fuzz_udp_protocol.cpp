// libFuzzer target: the UDP controller protocol's decoders, which read datagrams from the
// network. Any input must give a definite status; an accepted packet must be consistent
// (1..8 channels, finite values) and re-encode to a packet that decodes to the same content.
// Version 2 twice: the input as a datagram (the checks before the tag), and the input as a
// datagram's content tagged with the test key, so that what follows the tag check is fuzzed
// too (random bytes almost never carry a valid HMAC).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "rpsd/node/udp_controller_protocol.h"

namespace udp = rpsd::node::udp_protocol;

namespace {

const rpsd::node::UdpAuthenticator& test_key() {
  static const std::array<std::byte, 32> bytes = [] {
    std::array<std::byte, 32> b{};
    for (std::size_t i = 0; i < b.size(); ++i) b[i] = static_cast<std::byte>(0x5a ^ i);
    return b;
  }();
  static const rpsd::node::UdpAuthenticator key(bytes);
  return key;
}

void check_command(const udp::ControllerCommand& command) {
  if (command.channels < 1 || command.channels > 8) __builtin_trap();
  for (int c = 0; c < command.channels; ++c) {
    if (!std::isfinite(command.displacement_m[c])) __builtin_trap();
  }
}

void check_reply(const udp::ControllerReply& reply) {
  if (reply.channels < 1 || reply.channels > 8) __builtin_trap();
  for (int c = 0; c < reply.channels; ++c) {
    if (!std::isfinite(reply.displacement_m[c]) || !std::isfinite(reply.force_n[c])) __builtin_trap();
  }
}

void version_1(std::span<const std::byte> bytes) {
  udp::ControllerCommand command;
  if (udp::decode_command(bytes, command) == udp::PacketStatus::kOk) {
    check_command(command);
    udp::CommandPacket again;
    udp::ControllerCommand back;
    if (udp::encode_command(command, again) != udp::PacketStatus::kOk) __builtin_trap();
    if (udp::decode_command(again, back) != udp::PacketStatus::kOk || back.sequence != command.sequence)
      __builtin_trap();
  }
  udp::ControllerReply reply;
  if (udp::decode_reply(bytes, reply) == udp::PacketStatus::kOk) {
    check_reply(reply);
    udp::ReplyPacket again;
    udp::ControllerReply back;
    if (udp::encode_reply(reply, again) != udp::PacketStatus::kOk) __builtin_trap();
    if (udp::decode_reply(again, back) != udp::PacketStatus::kOk || back.sequence != reply.sequence) __builtin_trap();
  }
}

void version_2(std::span<const std::byte> bytes) {
  const auto& key = test_key();
  udp::ControllerCommand command;
  udp::Session session;
  if (udp::decode_command(bytes, key, command, session) == udp::PacketStatus::kOk) {
    check_command(command);
    udp::CommandPacketV2 again;
    udp::ControllerCommand back;
    udp::Session back_session;
    if (udp::encode_command(command, session, key, again) != udp::PacketStatus::kOk) __builtin_trap();
    if (udp::decode_command(again, key, back, back_session) != udp::PacketStatus::kOk ||
        back.sequence != command.sequence || !(back_session == session))
      __builtin_trap();
  }
  udp::ControllerReply reply;
  if (udp::decode_reply(bytes, key, reply, session) == udp::PacketStatus::kOk) {
    check_reply(reply);
    udp::ReplyPacketV2 again;
    udp::ControllerReply back;
    udp::Session back_session;
    if (udp::encode_reply(reply, session, key, again) != udp::PacketStatus::kOk) __builtin_trap();
    if (udp::decode_reply(again, key, back, back_session) != udp::PacketStatus::kOk ||
        back.sequence != reply.sequence || !(back_session == session))
      __builtin_trap();
  }
}

// The input's first bytes as the content of a version 2 datagram of `Size` bytes, tagged.
template <std::size_t Size>
void version_2_tagged(std::span<const std::byte> bytes) {
  constexpr std::size_t content = Size - rpsd::node::kUdpTagBytes;
  if (bytes.size() < content) return;
  std::array<std::byte, Size> datagram{};
  std::copy_n(bytes.begin(), content, datagram.begin());
  test_key().tag(std::span<const std::byte>(datagram.data(), content),
                 std::span<std::byte, rpsd::node::kUdpTagBytes>(datagram.data() + content, rpsd::node::kUdpTagBytes));
  version_2(datagram);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
  version_1(bytes);
  version_2(bytes);
  version_2_tagged<udp::kCommandBytesV2>(bytes);
  version_2_tagged<udp::kReplyBytesV2>(bytes);
  return 0;
}
