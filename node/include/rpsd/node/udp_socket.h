// A small owner of one IPv4 UDP socket for the controller adapter and its emulator:
// non-blocking datagrams, waits with a timeout, no system headers in the interface.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace rpsd::node {

struct Ipv4Endpoint {
  std::array<std::uint8_t, 4> address{};  // in dotted order: 127.0.0.1 is {127, 0, 0, 1}
  std::uint16_t port = 0;

  // Parses a dotted IPv4 address ("192.168.1.20"); throws std::invalid_argument naming
  // `what` and the text. Not real-time safe.
  static Ipv4Endpoint parse(const std::string& address, std::uint16_t port, const std::string& what);
  std::string to_string() const;
  bool operator==(const Ipv4Endpoint&) const = default;
};

class UdpSocket {
 public:
  // Opens a non-blocking socket bound to `local` (port 0: any free port). Throws
  // std::runtime_error with the system's reason. Not real-time safe.
  explicit UdpSocket(const Ipv4Endpoint& local);
  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  ~UdpSocket();

  // The bound port (the one the system chose when asked for 0).
  std::uint16_t local_port() const { return local_port_; }

  // Sends one datagram; false when the system refused it. Real-time safe.
  bool send_to(std::span<const std::byte> datagram, const Ipv4Endpoint& to) noexcept;

  enum class Wait : std::uint8_t { kReadable, kTimeout, kError };
  // Waits until a datagram is queued or timeout_s passes (ppoll; an interrupting signal
  // returns kTimeout early). Real-time safe.
  Wait wait_readable(double timeout_s) noexcept;

  static constexpr long kNothingQueued = -1;
  static constexpr long kReceiveError = -2;
  // Takes one queued datagram without waiting. Returns its full size (which may exceed the
  // buffer: the rest is discarded), kNothingQueued or kReceiveError. `from` gets the
  // sender. Real-time safe.
  long receive(std::span<std::byte> buffer, Ipv4Endpoint& from) noexcept;

 private:
  int fd_ = -1;
  std::uint16_t local_port_ = 0;
};

// Seconds on CLOCK_MONOTONIC. Real-time safe.
double monotonic_seconds() noexcept;

}  // namespace rpsd::node
