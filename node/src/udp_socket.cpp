#include "rpsd/node/udp_socket.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include "ipv4_sockaddr.h"

namespace rpsd::node {

Ipv4Endpoint Ipv4Endpoint::parse(const std::string& address, std::uint16_t port, const std::string& what) {
  in_addr parsed{};
  if (inet_pton(AF_INET, address.c_str(), &parsed) != 1) {
    throw std::invalid_argument(what + ": expected a dotted IPv4 address such as 192.168.1.20, got \"" + address +
                                "\"");
  }
  Ipv4Endpoint endpoint;
  std::memcpy(endpoint.address.data(), &parsed.s_addr, 4);
  endpoint.port = port;
  return endpoint;
}

std::string Ipv4Endpoint::to_string() const {
  return std::to_string(address[0]) + "." + std::to_string(address[1]) + "." + std::to_string(address[2]) + "." +
         std::to_string(address[3]) + ":" + std::to_string(port);
}

UdpSocket::UdpSocket(const Ipv4Endpoint& local) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("UDP socket: ") + std::strerror(errno));
  const sockaddr_in address = to_sockaddr(local);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("UDP socket: cannot bind " + local.to_string() + ": " + std::strerror(error));
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &length);
  local_port_ = ntohs(bound.sin_port);
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept : fd_(other.fd_), local_port_(other.local_port_) { other.fd_ = -1; }

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    local_port_ = other.local_port_;
    other.fd_ = -1;
  }
  return *this;
}

UdpSocket::~UdpSocket() {
  if (fd_ >= 0) ::close(fd_);
}

bool UdpSocket::send_to(std::span<const std::byte> datagram, const Ipv4Endpoint& to) noexcept {
  const sockaddr_in address = to_sockaddr(to);
  const ssize_t sent = ::sendto(fd_, datagram.data(), datagram.size(), MSG_DONTWAIT | MSG_NOSIGNAL,
                                reinterpret_cast<const sockaddr*>(&address), sizeof address);
  return sent == static_cast<ssize_t>(datagram.size());
}

UdpSocket::Wait UdpSocket::wait_readable(double timeout_s) noexcept {
  if (!(timeout_s > 0.0)) timeout_s = 0.0;
  timespec timeout{};
  timeout.tv_sec = static_cast<time_t>(timeout_s);
  timeout.tv_nsec = static_cast<long>((timeout_s - static_cast<double>(timeout.tv_sec)) * 1e9);
  if (timeout.tv_nsec > 999'999'999) timeout.tv_nsec = 999'999'999;
  pollfd descriptor{fd_, POLLIN, 0};
  const int ready = ::ppoll(&descriptor, 1, &timeout, nullptr);
  if (ready > 0) return (descriptor.revents & POLLIN) ? Wait::kReadable : Wait::kError;
  if (ready == 0 || errno == EINTR) return Wait::kTimeout;
  return Wait::kError;
}

long UdpSocket::receive(std::span<std::byte> buffer, Ipv4Endpoint& from) noexcept {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  // MSG_TRUNC: the real datagram size, so that an oversized datagram is seen as such.
  const ssize_t size = ::recvfrom(fd_, buffer.data(), buffer.size(), MSG_DONTWAIT | MSG_TRUNC,
                                  reinterpret_cast<sockaddr*>(&address), &length);
  if (size < 0) return (errno == EAGAIN || errno == EWOULDBLOCK) ? kNothingQueued : kReceiveError;
  from = from_sockaddr(address);
  return static_cast<long>(size);
}

double monotonic_seconds() noexcept {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace rpsd::node
