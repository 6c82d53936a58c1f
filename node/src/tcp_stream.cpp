#include "rpsd/node/tcp_stream.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <string>

#include "ipv4_sockaddr.h"

namespace rpsd::node {
namespace {

// Waits for `events` until the monotonic deadline: > 0 ready, 0 timeout, < 0 error.
int wait_for(int fd, short events, double deadline_s) noexcept {
  for (;;) {
    double left = deadline_s - monotonic_seconds();
    if (left < 0.0) left = 0.0;
    timespec timeout{};
    timeout.tv_sec = static_cast<time_t>(left);
    timeout.tv_nsec = std::min(999'999'999L, static_cast<long>((left - static_cast<double>(timeout.tv_sec)) * 1e9));
    pollfd descriptor{fd, events, 0};
    const int ready = ::ppoll(&descriptor, 1, &timeout, nullptr);
    if (ready > 0) return (descriptor.revents & (events | POLLHUP | POLLERR)) ? 1 : -1;
    if (ready == 0) return 0;
    if (errno != EINTR) return -1;
    if (monotonic_seconds() >= deadline_s) return 0;
  }
}

void tune(int fd) noexcept {
  const int on = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  ::setsockopt(fd, IPPROTO_TCP, TCP_QUICKACK, &on, sizeof on);
}

}  // namespace

TcpStream TcpStream::connect(const Ipv4Endpoint& peer, const Ipv4Endpoint& local, double timeout_s) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("TCP socket: ") + std::strerror(errno));
  TcpStream stream(fd, peer);
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  const sockaddr_in from = to_sockaddr(local);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&from), sizeof from) != 0) {
    throw std::runtime_error("TCP: cannot bind " + local.to_string() + ": " + std::strerror(errno));
  }
  const sockaddr_in to = to_sockaddr(peer);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0 && errno != EINPROGRESS) {
    throw std::runtime_error("TCP: cannot connect to " + peer.to_string() + ": " + std::strerror(errno));
  }
  const int ready = wait_for(fd, POLLOUT, monotonic_seconds() + timeout_s);
  int error = 0;
  socklen_t length = sizeof error;
  ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length);
  if (ready == 0)
    throw std::runtime_error("TCP: " + peer.to_string() + " did not accept a connection in " +
                             std::to_string(timeout_s) + " s");
  if (ready < 0 || error != 0) {
    throw std::runtime_error("TCP: cannot connect to " + peer.to_string() + ": " +
                             std::strerror(error != 0 ? error : errno));
  }
  tune(fd);
  return stream;
}

TcpStream::TcpStream(int fd, const Ipv4Endpoint& peer)
    : fd_(fd), peer_(peer), read_ahead_(std::make_unique<std::byte[]>(kReadAheadBytes)) {
  tune(fd);
}

TcpStream::TcpStream(TcpStream&& other) noexcept
    : fd_(other.fd_),
      peer_(other.peer_),
      read_ahead_(std::move(other.read_ahead_)),
      ahead_begin_(other.ahead_begin_),
      ahead_end_(other.ahead_end_) {
  other.fd_ = -1;
}

TcpStream& TcpStream::operator=(TcpStream&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = other.fd_;
    peer_ = other.peer_;
    read_ahead_ = std::move(other.read_ahead_);
    ahead_begin_ = other.ahead_begin_;
    ahead_end_ = other.ahead_end_;
    other.fd_ = -1;
  }
  return *this;
}

TcpStream::~TcpStream() { close(); }

void TcpStream::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

std::uint16_t TcpStream::local_port() const {
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  if (fd_ < 0 || ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &length) != 0) return 0;
  return ntohs(bound.sin_port);
}

bool TcpStream::sends_without_delay() const {
  int on = 0;
  socklen_t length = sizeof on;
  return fd_ >= 0 && ::getsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &on, &length) == 0 && on != 0;
}

void TcpStream::quick_ack() noexcept {
  // Linux clears TCP_QUICKACK after it acts: set again after every receive.
  const int on = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_QUICKACK, &on, sizeof on);
}

TcpStream::Io TcpStream::send_all(std::span<const std::byte> bytes, double deadline_s) noexcept {
  if (fd_ < 0) return Io::kClosed;
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      const int ready = wait_for(fd_, POLLOUT, deadline_s);
      if (ready == 0) return Io::kTimeout;
      if (ready < 0) return Io::kError;
      continue;
    }
    return (n < 0 && (errno == EPIPE || errno == ECONNRESET)) ? Io::kClosed : Io::kError;
  }
  return Io::kDone;
}

TcpStream::Io TcpStream::fill(double deadline_s) noexcept {
  if (fd_ < 0) return Io::kClosed;
  if (ahead_begin_ == ahead_end_) ahead_begin_ = ahead_end_ = 0;
  if (ahead_end_ == kReadAheadBytes) {  // shift what is left to the front
    std::memmove(read_ahead_.get(), read_ahead_.get() + ahead_begin_, ahead_end_ - ahead_begin_);
    ahead_end_ -= ahead_begin_;
    ahead_begin_ = 0;
    if (ahead_end_ == kReadAheadBytes) return Io::kOverflow;
  }
  for (;;) {
    const ssize_t n = ::recv(fd_, read_ahead_.get() + ahead_end_, kReadAheadBytes - ahead_end_, MSG_DONTWAIT);
    if (n > 0) {
      ahead_end_ += static_cast<std::size_t>(n);
      quick_ack();
      return Io::kDone;
    }
    if (n == 0) return Io::kClosed;
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) return errno == ECONNRESET ? Io::kClosed : Io::kError;
    const int ready = wait_for(fd_, POLLIN, deadline_s);
    if (ready == 0) return Io::kTimeout;
    if (ready < 0) return Io::kError;
  }
}

TcpStream::Io TcpStream::receive_exact(std::span<std::byte> bytes, double deadline_s) noexcept {
  std::size_t got = 0;
  return receive_resumable(bytes, got, deadline_s);
}

TcpStream::Io TcpStream::receive_resumable(std::span<std::byte> bytes, std::size_t& got, double deadline_s) noexcept {
  while (got < bytes.size()) {
    if (ahead_begin_ < ahead_end_) {
      const std::size_t n = std::min(bytes.size() - got, ahead_end_ - ahead_begin_);
      std::memcpy(bytes.data() + got, read_ahead_.get() + ahead_begin_, n);
      ahead_begin_ += n;
      got += n;
      continue;
    }
    const Io io = fill(deadline_s);
    if (io != Io::kDone) return io;
  }
  return Io::kDone;
}

TcpStream::Io TcpStream::receive_line(std::span<char> line, std::size_t& size, double deadline_s) noexcept {
  size = 0;
  std::size_t scanned = ahead_begin_;  // nothing is taken until the whole line is here
  for (;;) {
    for (; scanned < ahead_end_; ++scanned) {
      if (read_ahead_[scanned] != std::byte{'\n'}) continue;
      const std::size_t length = scanned + 1 - ahead_begin_;
      if (length > line.size()) return Io::kOverflow;
      std::memcpy(line.data(), read_ahead_.get() + ahead_begin_, length);
      ahead_begin_ += length;
      size = length;
      return Io::kDone;
    }
    if (ahead_end_ - ahead_begin_ >= line.size()) return Io::kOverflow;
    const std::size_t begin_before = ahead_begin_;
    const Io io = fill(deadline_s);  // may move the unread bytes to the front
    scanned -= begin_before - ahead_begin_;
    if (io != Io::kDone) return io;
  }
}

bool TcpStream::readable_now() noexcept {
  if (ahead_begin_ < ahead_end_) return true;
  return fd_ >= 0 && wait_for(fd_, POLLIN, 0.0) > 0;
}

TcpListener::TcpListener(const Ipv4Endpoint& local) {
  fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("TCP socket: ") + std::strerror(errno));
  const int on = 1;
  ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  const sockaddr_in address = to_sockaddr(local);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 || ::listen(fd_, 4) != 0) {
    const int error = errno;
    ::close(fd_);
    throw std::runtime_error("TCP: cannot listen on " + local.to_string() + ": " + std::strerror(error));
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &length);
  port_ = ntohs(bound.sin_port);
}

TcpListener::~TcpListener() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<TcpStream> TcpListener::accept(double timeout_s) {
  if (wait_for(fd_, POLLIN, monotonic_seconds() + timeout_s) <= 0) return std::nullopt;
  sockaddr_in address{};
  socklen_t length = sizeof address;
  const int fd = ::accept4(fd_, reinterpret_cast<sockaddr*>(&address), &length, SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd < 0) return std::nullopt;
  return TcpStream(fd, from_sockaddr(address));
}

}  // namespace rpsd::node
