// One TCP connection with OpenSees, and the listener that waits for one: exact-length
// messages (OpenSees frames nothing), per-message timeouts, and the options that keep a
// request/reply exchange fast. OpenSees writes its two messages per step with Nagle on; an
// end that neither sets TCP_NODELAY nor re-arms TCP_QUICKACK after each read waits for the
// delayed ACK (about 40 ms a step on loopback). Every wait has a deadline and ends at once
// when a stop is requested. No system headers in the interface.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace rpsd::opensees {

struct StreamOptions {
  bool low_latency = true;  // TCP_NODELAY, and TCP_QUICKACK re-armed after every read
};

// What ends a wait early: a flag (set from a signal handler or a test) and, optionally, a
// descriptor that becomes readable when it is set (apps/rpsd/stop_signals.h), polled beside
// the socket so that the wait ends the moment the flag is set. Without the descriptor the
// flag is read every kStopCheckIntervalS of a wait.
struct StopRequest {
  const std::atomic<bool>* flag = nullptr;
  int wake_fd = -1;
  bool requested() const noexcept { return flag != nullptr && flag->load(std::memory_order_relaxed); }
};
inline constexpr double kStopCheckIntervalS = 0.02;

enum class IoStatus : std::uint8_t {
  kOk,
  kClosed,   // the peer closed the connection before the message began
  kShort,    // the peer closed the connection, or went silent, inside a message
  kTimeout,  // nothing arrived in time, or the peer took nothing we wrote in time
  kError,    // the system refused (connection reset, ...)
  kStopped,  // a stop was requested while waiting
};
const char* io_status_text(IoStatus status);

class TcpStream {
 public:
  TcpStream() = default;
  TcpStream(int fd, StreamOptions options);
  TcpStream(TcpStream&& other) noexcept;
  TcpStream& operator=(TcpStream&& other) noexcept;
  TcpStream(const TcpStream&) = delete;
  TcpStream& operator=(const TcpStream&) = delete;
  ~TcpStream();

  // Connects to host:port (IPv4 dotted, or a name), trying again until timeout_s has passed
  // (an OpenSees adapter listens only once its analysis begins). Throws std::runtime_error
  // naming the address and the system's last reason. Not real-time safe.
  static TcpStream connect(const std::string& host, std::uint16_t port, double timeout_s, StreamOptions options = {});

  // Reads exactly buffer.size() bytes: the first within first_byte_timeout_s (< 0: no
  // limit), the rest within rest_timeout_s of it; kStopped as soon as `stop` is requested
  // (read before every wait). Real-time safe (it blocks, as a lock-step exchange does).
  IoStatus read_exact(std::span<std::byte> buffer, double first_byte_timeout_s, double rest_timeout_s,
                      const StopRequest& stop = {}) noexcept;
  // Writes every byte within timeout_s (< 0: no limit; kTimeout when the peer does not take
  // them, e.g. a client that never reads), or until `stop` is requested while the socket is
  // full. Never raises SIGPIPE. Real-time safe.
  IoStatus write_all(std::span<const std::byte> bytes, double timeout_s = -1.0, const StopRequest& stop = {}) noexcept;

  bool is_open() const { return fd_ >= 0; }
  void close() noexcept;
  // The peer's address as "a.b.c.d:port", and as an IPv4 address in host order (0: unknown).
  const std::string& peer() const { return peer_; }
  std::uint32_t peer_ipv4() const { return peer_ipv4_; }

 private:
  int fd_ = -1;
  StreamOptions options_;
  std::string peer_;
  std::uint32_t peer_ipv4_ = 0;
};

class TcpListener {
 public:
  // Listens on address:port (port 0: a free port the system picks). Throws
  // std::runtime_error naming the address and the system's reason. Not real-time safe.
  TcpListener(const std::string& address, std::uint16_t port);
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;
  ~TcpListener();

  std::uint16_t port() const { return port_; }
  // Waits up to timeout_s (< 0: no limit) for one connection; nullopt on timeout or once
  // `stop` is requested. Not real-time safe.
  std::optional<TcpStream> accept(double timeout_s, StreamOptions options = {}, const StopRequest& stop = {});

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace rpsd::opensees
