// An external controller in software: it speaks the controller side of the UDP protocol
// (udp_controller_protocol.h) and closes the loop with simulated plants. Tests run the
// hardware adapter against it; wrapped in a process it rehearses a hardware setup. It takes
// datagrams from its configured node only, commands only within a session the node began,
// and in version 2 only those tagged with the shared key for the current session.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/node/udp_authenticator.h"
#include "rpsd/node/udp_controller_protocol.h"
#include "rpsd/node/udp_socket.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

struct ControllerEmulatorConfig {
  std::string bind_host = "127.0.0.1";  // dotted IPv4
  std::uint16_t port = 0;               // 0: any free port (see ControllerEmulator::port())
  // The node: the one address and port it takes datagrams from (0: nobody, until set_node()).
  std::string node_host = "127.0.0.1";
  std::uint16_t node_port = 0;
  int protocol_version = udp_protocol::kVersion2;
  std::string key_file;        // version 2: where the key is (relative paths: to the emulator file)
  std::vector<std::byte> key;  // version 2: the key shared with the node (read_udp_key_file)

  // The keys of the `udp` section of an emulator file. Not real-time safe.
  static ControllerEmulatorConfig read(config::Source& udp);
  // Then, once every key of the file is read (so that a listing of the keys has seen them
  // all): checks the addresses and the version, and reads the key file, failing at the key.
  void check_and_load_key(config::Source& udp);
};

struct ControllerEmulatorCounters {
  std::uint64_t commands_applied = 0;
  std::uint64_t queries = 0;
  std::uint64_t sessions = 0;           // sessions begun by the node (a hello; a query in version 1)
  std::uint64_t foreign_datagrams = 0;  // from another address or port than the node's, ignored
  std::uint64_t unauthenticated = 0;    // version 2: a tag not made with the key, ignored
  std::uint64_t other_session = 0;      // version 2: a genuine datagram of another session (a replay), ignored
  std::uint64_t outside_session = 0;    // commands or queries before the node began a session, ignored
  std::uint64_t bad_packets = 0;        // undecodable datagrams, ignored
  std::uint64_t wrong_channels = 0;     // commands for another channel count, ignored
  std::uint64_t stale_commands = 0;     // sequence not newer than the last one taken in the session, ignored
  std::uint64_t refused_commands = 0;   // commands answered but not applied while in fault
  std::uint64_t send_errors = 0;
};

class ControllerEmulator {
 public:
  enum class Served : std::uint8_t {
    kApplied,  // a command advanced the plants by its period; replied
    kQueried,  // a query, a hello (or a command refused in fault) was answered without advancing
    kIgnored,  // a datagram was counted and dropped without a reply
    kTimeout,  // nothing arrived within the timeout
    kStopped,  // request_stop() was called
  };

  // `plants` (one per channel, not owned) must outlive the emulator. Binds the socket.
  // Throws std::invalid_argument (a bad address, version 2 without a valid key) or
  // std::runtime_error. Not real-time safe.
  ControllerEmulator(std::span<servo::Plant* const> plants, const ControllerEmulatorConfig& config);
  ~ControllerEmulator();

  std::uint16_t port() const { return socket_.local_port(); }
  int channels() const { return actuator_.channels(); }
  int protocol_version() const { return version_; }
  const Ipv4Endpoint& node() const { return node_; }
  // The node's address and port, when known only once its socket is bound. Call before
  // serving. Not real-time safe.
  void set_node(const Ipv4Endpoint& node) { node_ = node; }

  // Puts the plants at rest at the given displacements (one per channel) and ends any
  // session. Call before serving. Not real-time safe.
  void start(std::span<const double> initial_displacement_m);

  // Handles at most one datagram, waiting up to timeout_s for it: checks its sender, its tag
  // and session (version 2) and its sequence, advances the simulated actuator by the
  // packet's period with its command and replies to the node with the measurement at the end
  // of that period. Never waits longer than timeout_s, and returns within 50 ms of
  // request_stop().
  Served serve(double timeout_s);

  // Safe from any thread and from a signal handler.
  void request_stop() noexcept { stop_.store(true); }
  bool stop_requested() const noexcept { return stop_.load(); }

  // Emulates an interlock: while kFault, commands are answered with this status and not
  // applied. Safe from any thread.
  void set_status(udp_protocol::ControllerStatus status) noexcept { status_.store(status); }

  // Read from the serving thread, or after it has stopped.
  const ControllerEmulatorCounters& counters() const { return counters_; }
  // The measurement at the end of the last period applied (or at start).
  const servo::ActuatorReading& reading() const { return reading_; }

 private:
  // The datagram's command, if it is to be acted on (sender, tag, session, sequence checked);
  // kIgnored or kQueried when it was handled here (counted, a session begun).
  bool admit(std::span<const std::byte> bytes, const Ipv4Endpoint& from, udp_protocol::ControllerCommand& command,
             Served& handled);
  void reply(std::uint64_t sequence, udp_protocol::ControllerStatus status);

  servo::SimulatedActuator actuator_;
  UdpSocket socket_;
  Ipv4Endpoint node_;
  int version_ = udp_protocol::kVersion2;
  std::unique_ptr<UdpAuthenticator> key_;  // version 2
  udp_protocol::Session session_;
  bool in_session_ = false;
  ControllerEmulatorCounters counters_;
  servo::ActuatorReading reading_;
  std::array<std::byte, udp_protocol::kCommandBytesV2 + 1> receive_buffer_{};  // +1: oversized datagrams show
  udp_protocol::ReplyPacket reply_packet_{};
  udp_protocol::ReplyPacketV2 reply_packet_v2_{};
  std::uint64_t last_sequence_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<udp_protocol::ControllerStatus> status_{udp_protocol::ControllerStatus::kOk};
};

}  // namespace rpsd::node
