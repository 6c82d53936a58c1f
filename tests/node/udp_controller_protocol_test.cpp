// The controller protocol: the documented byte layout, exact round trips, and rejection of
// every malformed datagram (truncated, oversized, garbage, wrong magic/version, bad channel
// count, flags, period, status, non-finite values) without touching the output.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rpsd/node/udp_controller_protocol.h"

namespace rpsd::node::udp_protocol {
namespace {

ControllerCommand sample_command() {
  ControllerCommand c;
  c.sequence = 0x0102030405060708ull;
  c.channels = 3;
  c.period_s = 1.0 / 1024.0;
  c.displacement_m = {0.0125, -3.5e-3, 1e-300, 7.0, 8.0, 9.0, 10.0, 11.0};  // slots 3..7 unused
  return c;
}

ControllerReply sample_reply() {
  ControllerReply r;
  r.sequence = 42;
  r.channels = 2;
  r.status = ControllerStatus::kFault;
  r.displacement_m = {0.001, -0.002};
  r.force_n = {1.5e5, -2.5e4};
  return r;
}

std::uint64_t le(std::span<const std::byte> p, std::size_t at, int size) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= static_cast<std::uint64_t>(p[at + i]) << (8 * i);
  return v;
}

TEST(UdpProtocol, CommandLayoutIsTheDocumentedOne) {
  CommandPacket p{};
  ASSERT_EQ(encode_command(sample_command(), p), PacketStatus::kOk);
  EXPECT_EQ(p.size(), 88u);
  const char magic[] = {'R', 'P', 'S', 'C'};
  EXPECT_EQ(std::memcmp(p.data(), magic, 4), 0);
  EXPECT_EQ(le(p, 4, 2), 1u);               // version
  EXPECT_EQ(le(p, 6, 1), 3u);               // channels
  EXPECT_EQ(le(p, 7, 1), 0u);               // flags
  EXPECT_EQ(static_cast<int>(p[8]), 0x08);  // sequence, least significant byte first
  EXPECT_EQ(le(p, 8, 8), 0x0102030405060708ull);
  EXPECT_EQ(std::bit_cast<double>(le(p, 16, 8)), 1.0 / 1024.0);
  EXPECT_EQ(std::bit_cast<double>(le(p, 24, 8)), 0.0125);
  EXPECT_EQ(std::bit_cast<double>(le(p, 32, 8)), -3.5e-3);
  EXPECT_EQ(std::bit_cast<double>(le(p, 40, 8)), 1e-300);
  for (std::size_t at = 48; at < 88; ++at) EXPECT_EQ(static_cast<int>(p[at]), 0) << at;  // unused slots are zero

  ControllerCommand query = sample_command();
  query.query = true;
  query.period_s = 0.0;
  ASSERT_EQ(encode_command(query, p), PacketStatus::kOk);
  EXPECT_EQ(le(p, 7, 1), kFlagQuery);
}

TEST(UdpProtocol, ReplyLayoutIsTheDocumentedOne) {
  ReplyPacket p{};
  ASSERT_EQ(encode_reply(sample_reply(), p), PacketStatus::kOk);
  EXPECT_EQ(p.size(), 144u);
  const char magic[] = {'R', 'P', 'S', 'R'};
  EXPECT_EQ(std::memcmp(p.data(), magic, 4), 0);
  const auto at = [&](std::size_t offset) { return le(p, offset, 8); };
  EXPECT_EQ(static_cast<int>(p[6]), 2);  // channels
  EXPECT_EQ(static_cast<int>(p[7]), 1);  // status: fault
  EXPECT_EQ(at(8), 42u);
  EXPECT_EQ(std::bit_cast<double>(at(16)), 0.001);
  EXPECT_EQ(std::bit_cast<double>(at(24)), -0.002);
  EXPECT_EQ(std::bit_cast<double>(at(80)), 1.5e5);
  EXPECT_EQ(std::bit_cast<double>(at(88)), -2.5e4);
}

TEST(UdpProtocol, RoundTripsExactly) {
  CommandPacket cp{};
  ASSERT_EQ(encode_command(sample_command(), cp), PacketStatus::kOk);
  ControllerCommand c;
  ASSERT_EQ(decode_command(cp, c), PacketStatus::kOk);
  EXPECT_EQ(c.sequence, sample_command().sequence);
  EXPECT_EQ(c.channels, 3);
  EXPECT_FALSE(c.query);
  EXPECT_EQ(c.period_s, 1.0 / 1024.0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(c.displacement_m[i], sample_command().displacement_m[i]);
  for (int i = 3; i < kMaxChannels; ++i) EXPECT_EQ(c.displacement_m[i], 0.0);  // unused slots decode as zero

  ReplyPacket rp{};
  ASSERT_EQ(encode_reply(sample_reply(), rp), PacketStatus::kOk);
  ControllerReply r;
  ASSERT_EQ(decode_reply(rp, r), PacketStatus::kOk);
  EXPECT_EQ(r.sequence, 42u);
  EXPECT_EQ(r.status, ControllerStatus::kFault);
  EXPECT_EQ(r.displacement_m, sample_reply().displacement_m);
  EXPECT_EQ(r.force_n, sample_reply().force_n);

  // Extreme finite values and every channel count survive.
  std::mt19937_64 random(7);
  for (int n = 1; n <= kMaxChannels; ++n) {
    ControllerCommand in;
    in.sequence = random();
    in.channels = static_cast<std::uint8_t>(n);
    in.period_s = kMaxPeriodS;
    for (int i = 0; i < n; ++i) {
      in.displacement_m[i] = std::bit_cast<double>(random() & 0x7FEFFFFFFFFFFFFFull) * (i % 2 ? -1 : 1);  // finite
    }
    in.displacement_m[0] = std::numeric_limits<double>::max();
    ASSERT_EQ(encode_command(in, cp), PacketStatus::kOk);
    ASSERT_EQ(decode_command(cp, c), PacketStatus::kOk);
    EXPECT_EQ(std::memcmp(c.displacement_m.data(), in.displacement_m.data(), 8 * n), 0);
    EXPECT_EQ(c.sequence, in.sequence);
  }
}

TEST(UdpProtocol, EncodersRefuseInvalidContent) {
  CommandPacket p{};
  const CommandPacket untouched = p;
  ControllerCommand c = sample_command();
  c.displacement_m[1] = std::nan("");
  EXPECT_EQ(encode_command(c, p), PacketStatus::kNonFinite);
  c = sample_command();
  c.channels = 0;
  EXPECT_EQ(encode_command(c, p), PacketStatus::kBadChannels);
  c.channels = kMaxChannels + 1;
  EXPECT_EQ(encode_command(c, p), PacketStatus::kBadChannels);
  c = sample_command();
  for (double bad : {0.0, -1e-3, 2.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
    c.period_s = bad;
    EXPECT_EQ(encode_command(c, p), PacketStatus::kBadPeriod) << bad;
  }
  c = sample_command();
  c.query = true;  // a query carries period 0
  EXPECT_EQ(encode_command(c, p), PacketStatus::kBadPeriod);
  EXPECT_EQ(p, untouched);

  ReplyPacket rp{};
  ControllerReply r = sample_reply();
  r.force_n[1] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(encode_reply(r, rp), PacketStatus::kNonFinite);
  r = sample_reply();
  r.status = static_cast<ControllerStatus>(7);
  EXPECT_EQ(encode_reply(r, rp), PacketStatus::kBadStatus);
}

TEST(UdpProtocol, DecodersRejectMalformedDatagramsAndLeaveTheOutputAlone) {
  CommandPacket good{};
  ASSERT_EQ(encode_command(sample_command(), good), PacketStatus::kOk);
  const ControllerCommand sentinel = [] {
    ControllerCommand s;
    s.sequence = 99;
    return s;
  }();
  const auto expect_rejected = [&](std::span<const std::byte> bytes, PacketStatus expected, const char* what) {
    ControllerCommand out = sentinel;
    EXPECT_EQ(decode_command(bytes, out), expected) << what;
    EXPECT_EQ(out.sequence, 99u) << what;
  };
  expect_rejected({}, PacketStatus::kWrongSize, "empty");
  for (std::size_t n : {1u, 4u, 24u, 87u}) expect_rejected({good.data(), n}, PacketStatus::kWrongSize, "truncated");
  std::vector<std::byte> longer(good.begin(), good.end());
  longer.push_back(std::byte{0});
  expect_rejected(longer, PacketStatus::kWrongSize, "oversized");

  const auto mutated = [&](std::size_t at, std::byte value) {
    CommandPacket p = good;
    p[at] = value;
    return p;
  };
  expect_rejected(mutated(0, std::byte{'X'}), PacketStatus::kWrongMagic, "magic");
  ReplyPacket reply_bytes{};
  ASSERT_EQ(encode_reply(sample_reply(), reply_bytes), PacketStatus::kOk);
  ControllerCommand out;
  EXPECT_EQ(decode_command(std::span<const std::byte>(reply_bytes.data(), 88), out),
            PacketStatus::kWrongMagic);  // a reply is not a command
  expect_rejected(mutated(4, std::byte{2}), PacketStatus::kWrongVersion, "version");
  expect_rejected(mutated(6, std::byte{0}), PacketStatus::kBadChannels, "no channels");
  expect_rejected(mutated(6, std::byte{9}), PacketStatus::kBadChannels, "nine channels");
  expect_rejected(mutated(7, std::byte{2}), PacketStatus::kBadFlags, "unknown flag");
  expect_rejected(mutated(7, std::byte{1}), PacketStatus::kBadPeriod, "query with a period");
  expect_rejected(mutated(23, std::byte{0x7F}), PacketStatus::kBadPeriod,
                  "huge period");  // sign/exponent byte of the period
  expect_rejected(mutated(23, std::byte{0xBF}), PacketStatus::kBadPeriod, "negative period");
  CommandPacket nan_displacement = good;
  for (std::size_t i = 32; i < 40; ++i) nan_displacement[i] = std::byte{0xFF};  // channel 1: a NaN
  expect_rejected(nan_displacement, PacketStatus::kNonFinite, "NaN");
  CommandPacket nan_unused = good;
  for (std::size_t i = 80; i < 88; ++i) nan_unused[i] = std::byte{0xFF};  // slot 7 is not used by 3 channels
  EXPECT_EQ(decode_command(nan_unused, out), PacketStatus::kOk);
  EXPECT_EQ(out.displacement_m[7], 0.0);

  ReplyPacket bad_status = reply_bytes;
  bad_status[7] = std::byte{2};
  ControllerReply reply_out;
  EXPECT_EQ(decode_reply(bad_status, reply_out), PacketStatus::kBadStatus);
  ReplyPacket nan_force = reply_bytes;
  for (std::size_t i = 88; i < 96; ++i) nan_force[i] = std::byte{0xFF};  // force of channel 1
  EXPECT_EQ(decode_reply(nan_force, reply_out), PacketStatus::kNonFinite);
  EXPECT_EQ(decode_reply({reply_bytes.data(), 143}, reply_out), PacketStatus::kWrongSize);
  EXPECT_EQ(decode_reply(good, reply_out), PacketStatus::kWrongSize);
}

// Every single-byte change of a valid packet, and seeded random datagrams of every size up
// to 200 bytes: each decodes to a definite status, and anything accepted re-encodes to the
// same header and used slots (nothing outside the documented fields is taken in).
TEST(UdpProtocol, AnyBytesGiveADefiniteAnswer) {
  CommandPacket good{};
  ASSERT_EQ(encode_command(sample_command(), good), PacketStatus::kOk);
  ReplyPacket good_reply{};
  ASSERT_EQ(encode_reply(sample_reply(), good_reply), PacketStatus::kOk);
  long accepted = 0;
  for (std::size_t at = 0; at < good.size(); ++at) {
    for (int value = 0; value < 256; ++value) {
      CommandPacket p = good;
      p[at] = static_cast<std::byte>(value);
      ControllerCommand c;
      if (decode_command(p, c) == PacketStatus::kOk) {
        ++accepted;
        CommandPacket again{};
        ASSERT_EQ(encode_command(c, again), PacketStatus::kOk);
        // The header and the used slots round-trip; unused slots re-encode as zero.
        const std::size_t used = 24 + 8 * std::size_t{c.channels};
        EXPECT_EQ(std::memcmp(again.data(), p.data(), used), 0) << at << " " << value;
      }
    }
  }
  EXPECT_GT(accepted, 0);
  for (std::size_t at = 0; at < good_reply.size(); ++at) {
    for (int value = 0; value < 256; ++value) {
      ReplyPacket p = good_reply;
      p[at] = static_cast<std::byte>(value);
      ControllerReply r;
      if (decode_reply(p, r) == PacketStatus::kOk) {
        ReplyPacket again{};
        ASSERT_EQ(encode_reply(r, again), PacketStatus::kOk);
        const std::size_t used = 8 * std::size_t{r.channels};
        EXPECT_EQ(std::memcmp(again.data(), p.data(), 16 + used), 0) << at << " " << value;
        EXPECT_EQ(std::memcmp(again.data() + 80, p.data() + 80, used), 0) << at << " " << value;
      }
    }
  }
  std::mt19937 random(2024);
  std::vector<std::byte> bytes;
  for (int trial = 0; trial < 20000; ++trial) {
    bytes.resize(random() % 200);
    for (auto& b : bytes) b = static_cast<std::byte>(random());
    if (bytes.size() >= 4 && trial % 2 == 0) {  // half with a valid magic, to get past the first check
      bytes[0] = std::byte{'R'}, bytes[1] = std::byte{'P'}, bytes[2] = std::byte{'S'}, bytes[3] = std::byte{'C'};
    }
    ControllerCommand c;
    ControllerReply r;
    const PacketStatus sc = decode_command(bytes, c);
    const PacketStatus sr = decode_reply(bytes, r);
    EXPECT_TRUE(sc != PacketStatus::kOk || bytes.size() == kCommandBytes);
    EXPECT_TRUE(sr != PacketStatus::kOk || bytes.size() == kReplyBytes);
  }
}

}  // namespace
}  // namespace rpsd::node::udp_protocol
