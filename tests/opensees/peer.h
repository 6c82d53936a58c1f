// A scripted peer on loopback for the OpenSees protocol tests: what an OpenSees element would
// send (sizes, requests of data_size doubles), written and read as raw bytes.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rpsd/opensees/tcp_stream.h"

namespace rpsd::opensees::test {

inline void write_ints(TcpStream& s, const std::array<std::int32_t, 11>& sizes) {
  ASSERT_EQ(s.write_all(std::as_bytes(std::span<const std::int32_t>(sizes))), IoStatus::kOk);
}

// One request: `values` first, zeros up to data_size.
inline void write_request(TcpStream& s, int data_size, std::initializer_list<double> values) {
  std::vector<double> message(static_cast<std::size_t>(data_size), 0.0);
  std::copy(values.begin(), values.end(), message.begin());
  ASSERT_EQ(s.write_all(std::as_bytes(std::span<const double>(message))), IoStatus::kOk);
}

// One request, as a client that does not mind the server having gone: the write's status.
inline IoStatus try_request(TcpStream& s, int data_size, std::initializer_list<double> values) {
  std::vector<double> message(static_cast<std::size_t>(data_size), 0.0);
  std::copy(values.begin(), values.end(), message.begin());
  return s.write_all(std::as_bytes(std::span<const double>(message)), 5.0);
}

// True once the server has closed the connection (what is left unread is discarded).
inline bool closed_by_server(TcpStream& s) {
  std::vector<std::byte> sink(65536);
  for (;;) {
    const IoStatus status = s.read_exact(std::span<std::byte>(sink).first(1), 30.0, 30.0);
    if (status == IoStatus::kTimeout) return false;
    if (status != IoStatus::kOk) return true;
  }
}

inline std::vector<double> read_reply(TcpStream& s, int data_size) {
  std::vector<double> reply(static_cast<std::size_t>(data_size), 0.0);
  EXPECT_EQ(s.read_exact(std::as_writable_bytes(std::span<double>(reply)), 5.0, 5.0), IoStatus::kOk);
  return reply;
}

}  // namespace rpsd::opensees::test
