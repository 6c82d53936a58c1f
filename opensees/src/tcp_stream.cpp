#include "rpsd/opensees/tcp_stream.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "steady_seconds.h"

namespace rpsd::opensees {
namespace {

enum class Wait : std::uint8_t { kReady, kTimeout, kStopped };

// Waits until fd is ready for `events`, the deadline (< 0: none) passes or a stop is
// requested (the flag read before every poll, the wake descriptor polled beside fd).
Wait wait_for(int fd, short events, double deadline_s, const StopRequest& stop) {
  constexpr int kSliceMs = static_cast<int>(kStopCheckIntervalS * 1000.0);
  for (;;) {
    if (stop.requested()) return Wait::kStopped;
    int timeout_ms = -1;
    if (deadline_s >= 0.0) {
      const double left = deadline_s - steady_now_s();
      if (left <= 0.0) return Wait::kTimeout;
      timeout_ms = static_cast<int>(std::ceil(left * 1000.0));
    }
    if (stop.flag != nullptr) timeout_ms = timeout_ms < 0 ? kSliceMs : std::min(timeout_ms, kSliceMs);
    std::array<pollfd, 2> p{pollfd{fd, events, 0}, pollfd{stop.wake_fd, POLLIN, 0}};
    const int n = ::poll(p.data(), stop.wake_fd >= 0 ? 2 : 1, timeout_ms);
    if (n < 0 && errno != EINTR) return Wait::kReady;  // let recv or send report the error
    if (n > 0 && p[0].revents != 0) return Wait::kReady;
    if (n > 0 && p[1].revents != 0) return Wait::kStopped;  // only a stop makes it readable
  }
}

void set_low_latency(int fd) {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  ::setsockopt(fd, IPPROTO_TCP, TCP_QUICKACK, &one, sizeof one);
}

std::string address_text(const sockaddr_in& a) {
  char text[INET_ADDRSTRLEN] = "";
  ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof text);
  return std::string(text) + ":" + std::to_string(ntohs(a.sin_port));
}

sockaddr_in resolve(const std::string& host, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  if (::inet_pton(AF_INET, host.c_str(), &a.sin_addr) == 1) return a;
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int rc = ::getaddrinfo(host.c_str(), nullptr, &hints, &found); rc != 0 || !found) {
    throw std::runtime_error("cannot resolve host \"" + host + "\": " + ::gai_strerror(rc));
  }
  a.sin_addr = reinterpret_cast<sockaddr_in*>(found->ai_addr)->sin_addr;
  ::freeaddrinfo(found);
  return a;
}

}  // namespace

const char* io_status_text(IoStatus status) {
  switch (status) {
    case IoStatus::kOk:
      return "ok";
    case IoStatus::kClosed:
      return "the peer closed the connection";
    case IoStatus::kShort:
      return "the peer stopped inside a message (a short message)";
    case IoStatus::kTimeout:
      return "nothing arrived in time";
    case IoStatus::kError:
      return "the connection failed";
    case IoStatus::kStopped:
      return "a stop was requested";
  }
  return "unknown";
}

TcpStream::TcpStream(int fd, StreamOptions options) : fd_(fd), options_(options) {
  if (options_.low_latency) set_low_latency(fd_);
  sockaddr_in a{};
  socklen_t length = sizeof a;
  if (::getpeername(fd_, reinterpret_cast<sockaddr*>(&a), &length) == 0 && a.sin_family == AF_INET) {
    peer_ = address_text(a);
    peer_ipv4_ = ntohl(a.sin_addr.s_addr);
  }
}

TcpStream::TcpStream(TcpStream&& other) noexcept
    : fd_(other.fd_), options_(other.options_), peer_(std::move(other.peer_)), peer_ipv4_(other.peer_ipv4_) {
  other.fd_ = -1;
}

TcpStream& TcpStream::operator=(TcpStream&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = other.fd_;
    options_ = other.options_;
    peer_ = std::move(other.peer_);
    peer_ipv4_ = other.peer_ipv4_;
    other.fd_ = -1;
  }
  return *this;
}

TcpStream::~TcpStream() { close(); }

void TcpStream::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

TcpStream TcpStream::connect(const std::string& host, std::uint16_t port, double timeout_s, StreamOptions options) {
  const sockaddr_in to = resolve(host, port);
  const double deadline = steady_now_s() + timeout_s;
  int last_error = 0;
  for (;;) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw std::runtime_error(std::string("cannot open a TCP socket: ") + std::strerror(errno));
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) == 0) return TcpStream(fd, options);
    last_error = errno;
    ::close(fd);
    if (steady_now_s() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  throw std::runtime_error("no OpenSees answered at " + address_text(to) + " within " + std::to_string(timeout_s) +
                           " s (" + std::strerror(last_error) + ")");
}

IoStatus TcpStream::read_exact(std::span<std::byte> buffer, double first_byte_timeout_s, double rest_timeout_s,
                               const StopRequest& stop) noexcept {
  if (fd_ < 0) return IoStatus::kError;
  std::size_t done = 0;
  double deadline = first_byte_timeout_s < 0.0 ? -1.0 : steady_now_s() + first_byte_timeout_s;
  while (done < buffer.size()) {
    const Wait waited = wait_for(fd_, POLLIN, deadline, stop);
    if (waited == Wait::kStopped) return IoStatus::kStopped;
    if (waited == Wait::kTimeout) return done == 0 ? IoStatus::kTimeout : IoStatus::kShort;
    const ssize_t n = ::recv(fd_, buffer.data() + done, buffer.size() - done, 0);
    if (n == 0) return done == 0 ? IoStatus::kClosed : IoStatus::kShort;
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      return IoStatus::kError;
    }
    if (done == 0) deadline = rest_timeout_s < 0.0 ? -1.0 : steady_now_s() + rest_timeout_s;
    done += static_cast<std::size_t>(n);
  }
  if (options_.low_latency) {
    // Linux clears quick-ack mode on its own; re-arming it acknowledges the next segment at
    // once, so the peer's second small write is not held back by Nagle.
    const int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_QUICKACK, &one, sizeof one);
  }
  return IoStatus::kOk;
}

IoStatus TcpStream::write_all(std::span<const std::byte> bytes, double timeout_s, const StopRequest& stop) noexcept {
  if (fd_ < 0) return IoStatus::kError;
  const double deadline = timeout_s < 0.0 ? -1.0 : steady_now_s() + timeout_s;
  std::size_t done = 0;
  while (done < bytes.size()) {
    // Never blocking in send: a peer that reads nothing fills the socket, and the wait for
    // room is the one that sees the deadline and the stop.
    const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n >= 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) {
      const Wait waited = wait_for(fd_, POLLOUT, deadline, stop);
      if (waited == Wait::kStopped) return IoStatus::kStopped;
      if (waited == Wait::kTimeout) return IoStatus::kTimeout;
      continue;
    }
    return errno == EPIPE || errno == ECONNRESET ? IoStatus::kClosed : IoStatus::kError;
  }
  return IoStatus::kOk;
}

TcpListener::TcpListener(const std::string& address, std::uint16_t port) {
  const sockaddr_in at = resolve(address, port);
  // Non-blocking: a connection that is reset between poll and accept4 leaves nothing to wait on.
  fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("cannot open a TCP socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&at), sizeof at) != 0 || ::listen(fd_, 1) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("cannot listen on " + address_text(at) + ": " + reason);
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &length);
  port_ = ntohs(bound.sin_port);
}

TcpListener::~TcpListener() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<TcpStream> TcpListener::accept(double timeout_s, StreamOptions options, const StopRequest& stop) {
  const double deadline = timeout_s < 0.0 ? -1.0 : steady_now_s() + timeout_s;
  for (;;) {
    if (wait_for(fd_, POLLIN, deadline, stop) != Wait::kReady) return std::nullopt;
    const int fd = ::accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd >= 0) return TcpStream(fd, options);
    if (errno != EINTR && errno != ECONNABORTED && errno != EAGAIN) {
      throw std::runtime_error(std::string("accept failed: ") + std::strerror(errno));
    }
  }
}

}  // namespace rpsd::opensees
