#include "rpsd/node/speedgoat_link.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

namespace rpsd::node {

SpeedgoatLink::SpeedgoatLink(SpeedgoatTransport transport, const Ipv4Endpoint& target, const Ipv4Endpoint& local,
                             std::size_t vector_bytes)
    : transport_(transport),
      target_(target),
      local_(local),
      vector_bytes_(vector_bytes),
      partial_(vector_bytes),
      datagram_(vector_bytes + 1) {
  if (transport_ == SpeedgoatTransport::kUdp) udp_.emplace(local_);
}

std::uint16_t SpeedgoatLink::local_port() const {
  if (udp_) return udp_->local_port();
  return tcp_ ? tcp_->local_port() : 0;
}

void SpeedgoatLink::connect(double deadline_s) {
  partial_bytes_ = 0;
  const double timeout_s = std::max(0.0, deadline_s - monotonic_seconds());
  if (transport_ == SpeedgoatTransport::kTcp) {
    // A target that is not listening yet (its model still loading) is asked again every 100 ms.
    tcp_.reset();
    for (;;) {
      try {
        tcp_.emplace(TcpStream::connect(target_, local_, std::max(0.0, deadline_s - monotonic_seconds())));
        return;
      } catch (const std::runtime_error&) {
        if (monotonic_seconds() + 0.1 >= deadline_s) throw;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    }
  }
  udp_answered_ = false;
  const std::byte hello[1] = {std::byte{'a'}};
  while (!udp_answered_ && monotonic_seconds() < deadline_s) {
    if (!udp_->send_to(hello, target_)) ++counters_.send_errors;
    const double retry_s = std::min(deadline_s, monotonic_seconds() + 0.1);
    for (;;) {
      Ipv4Endpoint from;
      const long size = udp_->receive(datagram_, from);
      if (size >= 0 && from == target_) {
        udp_answered_ = true;
        break;
      }
      if (size >= 0) ++counters_.foreign_datagrams;
      if (size >= 0) continue;
      const double left_s = retry_s - monotonic_seconds();
      if (left_s <= 0.0) break;
      udp_->wait_readable(left_s);
    }
  }
  if (!udp_answered_) {
    throw std::runtime_error("Speedgoat target " + target_.to_string() +
                             " (UDP) did not answer the node's 'a' within " + std::to_string(timeout_s) + " s");
  }
}

SpeedgoatLink::Io SpeedgoatLink::send(std::span<const std::byte> vector, double deadline_s) noexcept {
  if (transport_ == SpeedgoatTransport::kUdp) {
    if (!udp_->send_to(vector, target_)) {
      ++counters_.send_errors;
      return Io::kError;
    }
    ++counters_.vectors_sent;
    return Io::kDone;
  }
  if (!tcp_) return Io::kClosed;
  switch (tcp_->send_all(vector, deadline_s)) {
    case TcpStream::Io::kDone:
      ++counters_.vectors_sent;
      return Io::kDone;
    case TcpStream::Io::kClosed:
      return Io::kClosed;
    case TcpStream::Io::kTimeout:
      return Io::kTimeout;
    default:
      ++counters_.send_errors;
      return Io::kError;
  }
}

SpeedgoatLink::Io SpeedgoatLink::receive(std::span<std::byte> vector, double deadline_s) noexcept {
  if (transport_ == SpeedgoatTransport::kUdp) return receive_datagram(vector, deadline_s);
  if (!tcp_) return Io::kClosed;
  switch (tcp_->receive_resumable(partial_, partial_bytes_, deadline_s)) {
    case TcpStream::Io::kDone:
      std::memcpy(vector.data(), partial_.data(), vector_bytes_);
      partial_bytes_ = 0;
      ++counters_.vectors_received;
      return Io::kDone;
    case TcpStream::Io::kTimeout:
      return Io::kTimeout;
    case TcpStream::Io::kClosed:
      return Io::kClosed;
    default:
      ++counters_.receive_errors;
      return Io::kError;
  }
}

SpeedgoatLink::Io SpeedgoatLink::receive_datagram(std::span<std::byte> vector, double deadline_s) noexcept {
  for (;;) {
    Ipv4Endpoint from;
    const long size = udp_->receive(datagram_, from);
    if (size == UdpSocket::kReceiveError) {
      ++counters_.receive_errors;
      return Io::kError;
    }
    if (size >= 0) {
      if (!(from == target_)) {
        ++counters_.foreign_datagrams;
      } else if (static_cast<std::size_t>(size) != vector_bytes_) {
        ++counters_.bad_packets;
      } else {
        std::memcpy(vector.data(), datagram_.data(), vector_bytes_);
        ++counters_.vectors_received;
        return Io::kDone;
      }
      continue;
    }
    const double left_s = deadline_s - monotonic_seconds();
    if (left_s <= 0.0) return Io::kTimeout;
    if (udp_->wait_readable(left_s) == UdpSocket::Wait::kError) {
      ++counters_.receive_errors;
      return Io::kError;
    }
  }
}

void SpeedgoatLink::close() noexcept {
  if (tcp_) tcp_->close();
  udp_answered_ = false;
  partial_bytes_ = 0;
}

}  // namespace rpsd::node
