// Ipv4Endpoint to and from the system's sockaddr_in, for the UDP and TCP sockets alike.
#pragma once

#include <netinet/in.h>

#include <cstring>

#include "rpsd/node/udp_socket.h"

namespace rpsd::node {

inline sockaddr_in to_sockaddr(const Ipv4Endpoint& endpoint) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(endpoint.port);
  std::memcpy(&address.sin_addr.s_addr, endpoint.address.data(), 4);  // already network order
  return address;
}

inline Ipv4Endpoint from_sockaddr(const sockaddr_in& address) {
  Ipv4Endpoint endpoint;
  std::memcpy(endpoint.address.data(), &address.sin_addr.s_addr, 4);
  endpoint.port = ntohs(address.sin_port);
  return endpoint;
}

}  // namespace rpsd::node
