// What the UDP link's tests share: a test key, an emulator and an adapter configured for each
// other on 127.0.0.1 (the adapter's port is known once it is bound: pair() tells the
// emulator), and a thread serving the emulator.
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/udp_controller_actuator.h"

namespace rpsd::node::testing {

inline std::vector<std::byte> test_key(std::uint8_t seed = 1) {
  std::vector<std::byte> key(32);
  for (std::size_t i = 0; i < key.size(); ++i) key[i] = static_cast<std::byte>(seed * 37 + i * 11);
  return key;
}

inline Ipv4Endpoint loopback(std::uint16_t port) { return Ipv4Endpoint::parse("127.0.0.1", port, "test"); }

inline ControllerEmulatorConfig emulator_config(int version = udp_protocol::kVersion2,
                                                const std::vector<std::byte>& key = test_key()) {
  ControllerEmulatorConfig config;
  config.protocol_version = version;
  if (version == udp_protocol::kVersion2) config.key = key;
  return config;
}

inline UdpControllerParameters adapter_config(const ControllerEmulator& emulator, int channels,
                                              const std::vector<std::byte>& key = test_key()) {
  UdpControllerParameters config;
  config.channels = channels;
  config.controller_host = "127.0.0.1";
  config.controller_port = emulator.port();
  config.local_host = "127.0.0.1";
  config.reply_timeout_s = 2.0;  // generous: a loaded machine must not turn into a missed reply
  config.protocol_version = emulator.protocol_version();
  if (config.protocol_version == udp_protocol::kVersion2) config.key = key;
  return config;
}

// The emulator takes datagrams from this adapter only.
inline void pair(ControllerEmulator& emulator, const UdpControllerActuator& adapter) {
  emulator.set_node(loopback(adapter.local_port()));
}

// Serves the emulator on its own thread until destroyed.
class Serving {
 public:
  explicit Serving(ControllerEmulator& emulator)
      : thread_([this, &emulator] {
          while (!stop_.load()) emulator.serve(0.01);
        }) {}
  ~Serving() {
    stop_.store(true);
    thread_.join();
  }
  Serving(const Serving&) = delete;
  Serving& operator=(const Serving&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rpsd::node::testing
