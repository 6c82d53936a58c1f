// The node's end of the connection to a Speedgoat target running OpenFresco's model: whole
// fixed-size vectors over TCP (a byte stream of them, TcpStream: no Nagle, quick acks) or
// UDP (one datagram each, from the target's address and port only), every wait bounded by a
// monotonic deadline. A TCP vector cut by a deadline is resumed by the next receive.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rpsd/node/tcp_stream.h"
#include "rpsd/node/udp_socket.h"

namespace rpsd::node {

enum class SpeedgoatTransport : std::uint8_t { kTcp, kUdp };

struct SpeedgoatLinkCounters {
  std::uint64_t vectors_sent = 0;
  std::uint64_t vectors_received = 0;
  std::uint64_t foreign_datagrams = 0;  // UDP: from another address or port than the target's, dropped
  std::uint64_t bad_packets = 0;        // UDP: a datagram of another size than a vector, dropped
  std::uint64_t send_errors = 0;
  std::uint64_t receive_errors = 0;
};

class SpeedgoatLink {
 public:
  enum class Io : std::uint8_t {
    kDone,     // the whole vector moved
    kTimeout,  // the deadline passed first
    kClosed,   // TCP: the target closed the connection
    kError,    // the system refused (this side)
  };

  // UDP binds `local` here (throws std::runtime_error); TCP binds it when connecting.
  // Not real-time safe.
  SpeedgoatLink(SpeedgoatTransport transport, const Ipv4Endpoint& target, const Ipv4Endpoint& local,
                std::size_t vector_bytes);

  // TCP: connects, asking again every 100 ms while the target refuses. UDP: sends the 1-byte datagram 'a' (OpenSees'
  // UDP_Socket) every 100 ms until a datagram from the target answers it (that datagram is consumed, as OpenSees does).
  // Throws std::runtime_error naming the target when the deadline passes. Not real-time safe.
  void connect(double deadline_s);
  // Real-time safe.
  Io send(std::span<const std::byte> vector, double deadline_s) noexcept;
  // One whole vector into `vector` (vector_bytes long). Real-time safe.
  Io receive(std::span<std::byte> vector, double deadline_s) noexcept;
  // TCP: closes the connection (the next connect() opens another). Not real-time safe.
  void close() noexcept;

  bool connected() const { return transport_ == SpeedgoatTransport::kUdp ? udp_answered_ : (tcp_ && tcp_->is_open()); }
  std::uint16_t local_port() const;
  SpeedgoatTransport transport() const { return transport_; }
  const Ipv4Endpoint& target() const { return target_; }
  const SpeedgoatLinkCounters& counters() const { return counters_; }

 private:
  Io receive_datagram(std::span<std::byte> vector, double deadline_s) noexcept;

  SpeedgoatTransport transport_;
  Ipv4Endpoint target_;
  Ipv4Endpoint local_;
  std::size_t vector_bytes_;
  std::optional<TcpStream> tcp_;
  std::optional<UdpSocket> udp_;
  bool udp_answered_ = false;
  std::vector<std::byte> partial_;  // TCP: the vector being received
  std::size_t partial_bytes_ = 0;
  std::vector<std::byte> datagram_;  // UDP: one more byte than a vector, so that oversized ones show
  SpeedgoatLinkCounters counters_;
};

}  // namespace rpsd::node
