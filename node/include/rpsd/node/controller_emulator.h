// An external controller in software: it speaks the controller side of the UDP protocol
// (udp_controller_protocol.h) and closes the loop with simulated plants. Tests run the
// hardware adapter against it; wrapped in a process it rehearses a hardware setup.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <string>

#include "rpsd/node/udp_controller_protocol.h"
#include "rpsd/node/udp_socket.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

struct ControllerEmulatorConfig {
  std::string bind_host = "127.0.0.1";  // dotted IPv4
  std::uint16_t port = 0;               // 0: any free port (see ControllerEmulator::port())
};

struct ControllerEmulatorCounters {
  std::uint64_t commands_applied = 0;
  std::uint64_t queries = 0;
  std::uint64_t bad_packets = 0;       // undecodable datagrams, ignored
  std::uint64_t wrong_channels = 0;    // commands for another channel count, ignored
  std::uint64_t stale_commands = 0;    // sequence not newer than the last one applied, ignored
  std::uint64_t refused_commands = 0;  // commands answered but not applied while in fault
  std::uint64_t send_errors = 0;
};

class ControllerEmulator {
 public:
  enum class Served : std::uint8_t {
    kApplied,  // a command advanced the plants by its period; replied
    kQueried,  // a query (or a command refused in fault) was answered without advancing
    kIgnored,  // a datagram was counted and dropped without a reply
    kTimeout,  // nothing arrived within the timeout
    kStopped,  // request_stop() was called
  };

  // `plants` (one per channel, not owned) must outlive the emulator. Binds the socket.
  // Throws std::invalid_argument or std::runtime_error. Not real-time safe.
  ControllerEmulator(std::span<servo::Plant* const> plants, const ControllerEmulatorConfig& config);

  std::uint16_t port() const { return socket_.local_port(); }
  int channels() const { return actuator_.channels(); }

  // Puts the plants at rest at the given displacements (one per channel). Call before
  // serving. Not real-time safe.
  void start(std::span<const double> initial_displacement_m);

  // Handles at most one datagram, waiting up to timeout_s for it: decodes it, advances the
  // simulated actuator by the packet's period with its command and replies to the sender
  // with the measurement at the end of that period. Never waits longer than timeout_s, and
  // returns within 50 ms of request_stop().
  Served serve(double timeout_s);

  // Safe from any thread and from a signal handler.
  void request_stop() noexcept { stop_.store(true); }
  bool stop_requested() const noexcept { return stop_.load(); }

  // Emulates an interlock: while kFault, commands are answered with this status and not
  // applied. Safe from any thread.
  void set_status(udp_protocol::ControllerStatus status) noexcept { status_.store(status); }

  // Read from the serving thread, or after it has stopped.
  const ControllerEmulatorCounters& counters() const { return counters_; }

 private:
  void reply(std::uint64_t sequence, udp_protocol::ControllerStatus status, const Ipv4Endpoint& to);

  servo::SimulatedActuator actuator_;
  UdpSocket socket_;
  ControllerEmulatorCounters counters_;
  servo::ActuatorReading reading_;
  std::array<std::byte, udp_protocol::kCommandBytes + 1> receive_buffer_{};  // +1: oversized datagrams show
  udp_protocol::ReplyPacket reply_packet_{};
  std::uint64_t last_sequence_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<udp_protocol::ControllerStatus> status_{udp_protocol::ControllerStatus::kOk};
};

}  // namespace rpsd::node
