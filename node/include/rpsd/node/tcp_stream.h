// One IPv4 TCP connection for the lab-controller adapters and their emulators: non-blocking,
// every wait bounded by a monotonic deadline, tuned against the latency trap (TCP_NODELAY so
// that no small message waits for Nagle; TCP_QUICKACK re-armed after each receive so that no
// acknowledgement is delayed), no system headers in the interface.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <span>

#include "rpsd/node/udp_socket.h"

namespace rpsd::node {

class TcpStream {
 public:
  enum class Io : unsigned char {
    kDone,      // every byte asked for moved
    kTimeout,   // the deadline passed first (bytes already moved stay moved)
    kClosed,    // the peer closed the connection
    kError,     // the system refused (reset, broken pipe)
    kOverflow,  // receive_line(): the buffer filled without a newline
  };

  // Connects to `peer` from `local` (port 0: any) before timeout_s passes. Throws
  // std::runtime_error naming the peer and the system's reason. Not real-time safe.
  static TcpStream connect(const Ipv4Endpoint& peer, const Ipv4Endpoint& local, double timeout_s);
  // Takes over an accepted socket (TcpListener). Not real-time safe.
  TcpStream(int fd, const Ipv4Endpoint& peer);
  TcpStream(TcpStream&& other) noexcept;
  TcpStream& operator=(TcpStream&& other) noexcept;
  TcpStream(const TcpStream&) = delete;
  TcpStream& operator=(const TcpStream&) = delete;
  ~TcpStream();

  const Ipv4Endpoint& peer() const { return peer_; }
  std::uint16_t local_port() const;
  bool is_open() const { return fd_ >= 0; }
  // Whether the system says Nagle's delay is off on this connection (TCP_NODELAY).
  bool sends_without_delay() const;

  // Sends every byte before the monotonic deadline (monotonic_seconds()). Real-time safe.
  Io send_all(std::span<const std::byte> bytes, double deadline_s) noexcept;
  // Receives exactly bytes.size() bytes before the deadline. Real-time safe.
  Io receive_exact(std::span<std::byte> bytes, double deadline_s) noexcept;
  // Fills bytes from `got` on before the deadline, adding what moved to `got`: a fixed-size
  // message cut by the deadline is resumed by the next call. Real-time safe.
  Io receive_resumable(std::span<std::byte> bytes, std::size_t& got, double deadline_s) noexcept;
  // Receives one line, up to and including '\n', into `line` (length in `size`, the newline
  // kept); bytes after it stay for the next call. Real-time safe: the buffer is the caller's
  // and the read-ahead one is allocated at construction.
  Io receive_line(std::span<char> line, std::size_t& size, double deadline_s) noexcept;
  // True when bytes are waiting to be read (nothing consumed). Real-time safe.
  bool readable_now() noexcept;
  // Closes the connection (the peer sees end of stream). Not real-time safe.
  void close() noexcept;

 private:
  Io fill(double deadline_s) noexcept;  // one wait and read into the read-ahead buffer
  void quick_ack() noexcept;

  int fd_ = -1;
  Ipv4Endpoint peer_;
  static constexpr std::size_t kReadAheadBytes = 8192;
  std::unique_ptr<std::byte[]> read_ahead_;
  std::size_t ahead_begin_ = 0, ahead_end_ = 0;
};

class TcpListener {
 public:
  // Listens on `local` (port 0: any free port). Throws std::runtime_error. Not real-time safe.
  explicit TcpListener(const Ipv4Endpoint& local);
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;
  ~TcpListener();
  std::uint16_t port() const { return port_; }
  // The next connection, waiting at most timeout_s (nullopt: none came). Not real-time safe.
  std::optional<TcpStream> accept(double timeout_s);

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace rpsd::node
