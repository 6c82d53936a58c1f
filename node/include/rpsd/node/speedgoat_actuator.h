// Hardware adapter: a Speedgoat (Simulink Real-Time) target running OpenFresco's hybrid
// controller model, spoken to as OpenFresco's ECSpeedgoat does (docs/lab-controllers.md):
// each command raises newTarget and waits for switchPC, lowers it and waits for switchPC to
// fall, then waits for atTarget and reads the DAQ signals; every vector is sent twice and the
// flags are waited for by draining whatever else comes. start() measures the offsets of the
// relative signals, as OpenFresco's setup() does, without asking anyone to press Enter. The
// target is pinned: TCP connects to it alone, UDP takes datagrams from its address and port only.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/node/actuator_link_report.h"
#include "rpsd/node/speedgoat_link.h"
#include "rpsd/node/speedgoat_signals.h"
#include "rpsd/servo/actuator.h"
#include "rpsd/servo/envelope.h"

namespace rpsd::node {

struct OwnedActuator;

struct SpeedgoatParameters {
  static constexpr std::string_view kName = "openfresco_speedgoat";
  static constexpr std::string_view kSummary =
      "a Speedgoat target running OpenFresco's hybrid controller model, over TCP or UDP (docs/lab-controllers.md)";
  static SpeedgoatParameters read(config::Source& section, int channels);
  static OwnedActuator make(const SpeedgoatParameters& config, int channels);
  servo::Envelope envelope() const { return rig; }
  // Why channel `channel` cannot be in `mode` (empty: it can): a channel in force control needs
  // a force control signal, and one in displacement control has none (rpsd would have no force
  // to send there). Not real-time safe.
  std::string control_mode_refusal(int channel, servo::ControlMode mode) const;

  int channels = 1;
  SpeedgoatTransport transport = SpeedgoatTransport::kTcp;
  std::string host = "127.0.0.1";  // the target (dotted IPv4)
  std::uint16_t port = 0;          // required
  std::string local_host = "0.0.0.0";
  std::uint16_t local_port = 0;  // UDP: the port the target's model sends to (0: any free one)
  speedgoat::SignalMap signals;
  // How long past the control period one command's whole handshake may take.
  double reply_timeout_s = 0.002;
  // More consecutive commands without a finished handshake than this: a latched kFault.
  int max_missed_replies = 3;
  double start_timeout_s = 5.0;     // start(): connecting, the offsets and the first move
  double start_tolerance_m = 1e-3;  // start(): largest |measured - initial| displacement accepted
  servo::Envelope rig;              // what the rig behind the target can do; required

  // Throws std::invalid_argument naming the field. Not real-time safe.
  void validate() const;
};

struct SpeedgoatCounters {
  std::uint64_t handshakes = 0;          // commands whose handshake finished
  std::uint64_t resumed_handshakes = 0;  // exchanges that went on with an unfinished one
  std::uint64_t drained_vectors = 0;     // stale, repeated or extra vectors read while a flag was awaited
  std::uint64_t missed_deadlines = 0;    // exchanges that ended before their handshake (kNoReply)
  std::uint64_t malformed_vectors = 0;   // flags other than 0 and 1, or a DAQ signal not finite
};

class SpeedgoatActuator final : public servo::Actuator, public ActuatorLinkReport {
 public:
  // Validates the config and, for UDP, binds the local socket. Not real-time safe.
  explicit SpeedgoatActuator(const SpeedgoatParameters& config);
  // Ends the session: newTarget = -1, sent twice.
  ~SpeedgoatActuator() override;

  int channels() const override { return config_.channels; }

  // Connects within start_timeout_s, reads the target's DAQ once it is at its target, takes
  // the offsets of the relative signals (sending the relative control signals' offsets twice),
  // checks the measured displacement against initial_displacement_m within start_tolerance_m
  // and commands the initial displacement with one handshake (no jump). Throws
  // std::runtime_error naming what failed. Clears a latched fault. Not real-time safe.
  void start(std::span<const double> initial_displacement_m) override;

  // One command's handshake, all of it before period_s + reply_timeout_s. When the deadline
  // passes first: kNoReply, and the next exchange resumes the same handshake (its own command
  // is not sent); more than max_missed_replies in a row, a closed connection, a malformed
  // vector or a non-finite command: a latched kFault, and the session is ended. Real-time
  // safe: no allocation, every wait bounded.
  servo::ActuatorStatus exchange(std::span<const double> command_m, double period_s,
                                 servo::ActuatorReading& reading) override;
  // Mixed control: a force channel's force command goes to its force control signal (its
  // displacement signal carries the node's displacement command: its measured position), and
  // each channel's mode to its control_mode signal, if it has one. Real-time safe.
  servo::ActuatorStatus exchange_mixed(std::span<const double> command_m, std::span<const double> force_command_n,
                                       std::span<const servo::ControlMode> mode, double period_s,
                                       servo::ActuatorReading& reading) override;
  bool controls_force(int channel) const override;

  std::string_view summary_key() const override { return "speedgoat_link"; }
  std::string describe_link() const override;
  nlohmann::json link_summary() const override;

  const SpeedgoatCounters& counters() const { return counters_; }
  const SpeedgoatLinkCounters& link_counters() const { return link_.counters(); }
  std::uint16_t local_port() const { return link_.local_port(); }
  // Each control signal's offset (signal units; 0 unless relative), each DAQ signal's, and
  // the DAQ signals the target sent at start.
  const std::vector<double>& control_offsets() const { return control_offset_; }
  const std::vector<double>& daq_offsets() const { return daq_offset_; }
  const std::vector<double>& initial_daq() const { return initial_daq_; }
  // Which side failed ("none", "target", "node") and why.
  const char* failed_side() const { return failed_side_; }
  const char* failure() const { return failure_; }
  // After a fault: why (a literal, so the node's heartbeat can carry it). Real-time safe.
  std::string_view fault_text() const noexcept override { return link_fault_ ? failure_ : ""; }

 private:
  enum class Phase : std::uint8_t { kIdle, kAwaitSwitchHigh, kAwaitSwitchLow, kAwaitAtTarget };
  enum class Step : std::uint8_t { kDone, kTimeout, kFault };

  // Writes the control signals of a command into the outgoing vector; false if not finite.
  bool compose(std::span<const double> command_m, double period_s) noexcept;
  // Sends the outgoing vector twice with newTarget = value.
  Step send_twice(double new_target, double deadline_s) noexcept;
  // Runs the handshake from its phase until it is done, the deadline passes or it fails.
  Step advance(double deadline_s) noexcept;
  // Reads one vector and checks its flags and DAQ signals.
  Step receive(double deadline_s) noexcept;
  void read_measurement(servo::ActuatorReading& reading) const noexcept;
  servo::ActuatorStatus fail(const char* side, const char* reason) noexcept;
  void end_session() noexcept;

  SpeedgoatParameters config_;
  SpeedgoatLink link_;
  std::vector<std::byte> out_;  // the PC's vector
  std::vector<std::byte> in_;   // the target's newest vector
  std::vector<double> control_offset_, daq_offset_, initial_daq_;
  std::array<double, servo::kMaxChannels> previous_m_{};
  std::array<double, servo::kMaxChannels> force_command_n_{};  // the newest force commands
  std::array<double, servo::kMaxChannels> control_mode_{};     // 0 displacement, 1 force control
  std::array<double, servo::kMaxChannels> previous_velocity_m_per_s_{};
  double time_s_ = 0.0;
  Phase phase_ = Phase::kIdle;
  int consecutive_missed_ = 0;
  bool link_fault_ = false;
  bool started_ = false;
  const char* failed_side_ = "none";
  const char* failure_ = "";
  SpeedgoatCounters counters_;
};

}  // namespace rpsd::node
