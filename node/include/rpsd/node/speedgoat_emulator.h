// A Speedgoat target in software, written from OpenFresco's client (ECSpeedgoat) and OpenSees'
// sockets, not from rpsd's adapter: it plays the hybrid-controller model's side of the
// handshake with simulated plants behind it, so that a node file can be rehearsed with no
// hardware and tests can drive the adapter. On newTarget's rise it takes the control signals
// as the new target and raises switchPC; on its fall it lowers switchPC, moves the plants
// from the previous target to the new one over step_duration_s and sends the at-target
// vector. It answers every vector it receives with its state vector. It serves one node:
// TCP from node_host only, one connection at a time; UDP the first node_host address that
// sends 'a' (or node_host:node_port).
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/node/tcp_stream.h"
#include "rpsd/node/udp_socket.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

struct SpeedgoatEmulatorConfig {
  // One entry of the target model's signal order: the channel and what the value is.
  struct Signal {
    int channel = 0;
    std::string
        quantity;  // control: displacement, velocity, acceleration, force, time; DAQ: displacement, force, unused
    double signal_per_si = 1.0;
  };
  bool udp = false;
  std::string bind_host = "127.0.0.1";
  std::uint16_t port = 0;  // 0: any free port (SpeedgoatEmulator::port())
  std::string node_host = "127.0.0.1";
  std::uint16_t node_port = 0;  // UDP: 0 takes the port of the first 'a' from node_host
  int vector_doubles = 256;
  std::vector<Signal> control;
  std::vector<Signal> daq;
  std::vector<double> daq_offsets;  // added to each DAQ signal (signal units): the transducers' zero
  double step_duration_s = 1.0 / 1024.0;
  // For tests and rehearsals of failures (0: never): after this many moves it sends nothing
  // more; the at-target vector of this move carries a NaN; or one double too many.
  int silent_after_moves = 0;
  int malformed_at_move = 0;
  int oversized_at_move = 0;

  // The `target` section of an emulator file. Not real-time safe.
  static SpeedgoatEmulatorConfig read(config::Source& target, int channels);
};

struct SpeedgoatEmulatorCounters {
  std::uint64_t sessions = 0;        // connections (TCP) or 'a' (UDP) taken
  std::uint64_t sessions_ended = 0;  // newTarget = -1 received
  std::uint64_t vectors_received = 0;
  std::uint64_t vectors_sent = 0;
  std::uint64_t moves = 0;              // targets reached
  std::uint64_t refused_clients = 0;    // TCP: a connection from elsewhere, or a second one
  std::uint64_t foreign_datagrams = 0;  // UDP: from anyone but the node
  std::uint64_t bad_packets = 0;        // UDP: a datagram of another size than a vector
  std::uint64_t send_errors = 0;
};

class SpeedgoatEmulator {
 public:
  // `plants` (one per channel, not owned) must outlive the emulator. Binds or listens.
  // Throws std::invalid_argument or std::runtime_error. Not real-time safe.
  SpeedgoatEmulator(std::span<servo::Plant* const> plants, const SpeedgoatEmulatorConfig& config);

  std::uint16_t port() const;
  // Puts the plants at rest there. Call before serving.
  void start(std::span<const double> initial_displacement_m);
  // Handles what arrives within timeout_s (a connection, a vector, a datagram); false when
  // nothing did. Returns within 50 ms of request_stop().
  bool serve(double timeout_s);
  void request_stop() noexcept { stop_.store(true); }

  // Read from the serving thread, or after it stopped.
  const SpeedgoatEmulatorCounters& counters() const { return counters_; }
  const servo::ActuatorReading& reading() const { return reading_; }
  // The newest target's force commands (N) and control modes, from its force and control_mode
  // signals: a channel with a force signal is in force control unless its control_mode says 0.
  std::span<const double> force_target_n() const { return force_target_n_; }
  std::span<const servo::ControlMode> control_mode() const { return mode_; }
  int channels() const { return actuator_.channels(); }
  // The node it serves ("none yet" until one came).
  std::string node() const;
  const SpeedgoatEmulatorConfig& config() const { return config_; }

 private:
  void take(const std::vector<unsigned char>& vector);
  void send_state(bool at_target_vector);
  void send_bytes(const unsigned char* bytes, std::size_t size);
  void accept_connections(double timeout_s);

  SpeedgoatEmulatorConfig config_;
  servo::SimulatedActuator actuator_;
  servo::ActuatorReading reading_;
  Ipv4Endpoint node_address_;
  std::optional<TcpListener> listener_;
  std::optional<TcpStream> connection_;
  std::optional<UdpSocket> socket_;
  std::optional<Ipv4Endpoint> udp_peer_;
  std::vector<unsigned char> incoming_;
  std::size_t incoming_bytes_ = 0;
  std::vector<double> target_m_, previous_target_m_;
  std::vector<double> force_target_n_;
  std::vector<servo::ControlMode> mode_;
  double new_target_ = 0.0;
  double switch_pc_ = 0.0;
  double at_target_ = 1.0;
  bool silent_ = false;
  SpeedgoatEmulatorCounters counters_;
  std::atomic<bool> stop_{false};
};

}  // namespace rpsd::node
