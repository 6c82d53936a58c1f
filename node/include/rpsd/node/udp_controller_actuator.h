// Hardware adapter: an external real-time controller (Speedgoat/xPC target, LabVIEW loop)
// that closes the servo loop itself and talks the UDP protocol of udp_controller_protocol.h
// (docs/udp-controller-protocol.md). Each control period sends one command datagram and
// waits for the reply that echoes its sequence number. It takes replies from the configured
// controller address and port only, and in version 2 (the default) only those tagged with the
// shared key for the session its start() began.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/servo/envelope.h"

#include "rpsd/node/actuator_link_report.h"
#include "rpsd/node/udp_authenticator.h"
#include "rpsd/node/udp_controller_protocol.h"
#include "rpsd/node/udp_socket.h"
#include "rpsd/servo/actuator.h"

namespace rpsd::node {

struct OwnedActuator;

struct UdpControllerParameters {
  static constexpr std::string_view kName = "udp_controller";
  static constexpr std::string_view kSummary =
      "a hardware controller that closes the servo loop itself, on UDP (docs/udp-controller-protocol.md)";
  static UdpControllerParameters read(config::Source& section, int channels);
  static OwnedActuator make(const UdpControllerParameters& config, int channels);
  servo::Envelope envelope() const { return rig; }
  // Why a channel cannot be in `mode` (empty: it can): the protocol has no force command.
  std::string control_mode_refusal(int /*channel*/, servo::ControlMode mode) const {
    return mode == servo::ControlMode::kForce ? "rpsd's UDP controller protocol (versions 1 and 2) carries a "
                                                "displacement command only, with no room for a control mode or a force"
                                              : "";
  }

  int channels = 1;                           // must equal the controller's
  std::string controller_host = "127.0.0.1";  // dotted IPv4
  std::uint16_t controller_port = 0;          // required
  std::string local_host = "0.0.0.0";         // address to bind (dotted IPv4)
  std::uint16_t local_port = 0;               // 0: any free port (a controller that filters needs a fixed one)
  // 2: every datagram authenticated with `key`; 1: nothing authenticated (legacy controllers).
  int protocol_version = udp_protocol::kVersion2;
  std::string key_file;        // where `key` came from, for messages
  std::vector<std::byte> key;  // version 2: the key shared with the controller (read_udp_key_file)
  // How long past the control period to wait for a reply: the controller answers at the end
  // of the period over which it applied the command, so the wait is period_s + this.
  double reply_timeout_s = 0.001;
  // More consecutive missing replies than this make exchange() report a latched kFault.
  int max_missed_replies = 3;
  double start_timeout_s = 1.0;     // start(): how long to try to reach the controller
  double start_tolerance_m = 1e-3;  // start(): largest |measured - initial| displacement accepted
  // What the rig behind the controller can do; a hardware node's file must state it.
  servo::Envelope rig;

  // Throws std::invalid_argument naming the field. Not real-time safe.
  void validate() const;
};
using UdpControllerConfig [[deprecated("renamed UdpControllerParameters (docs/migration.md)")]] =
    UdpControllerParameters;

struct UdpControllerCounters {
  std::uint64_t commands_sent = 0;
  std::uint64_t replies = 0;                  // matching replies taken
  std::uint64_t missed_replies = 0;           // periods without a matching reply in time
  std::uint64_t stale_replies = 0;            // replies to an older command, drained
  std::uint64_t bad_replies = 0;              // undecodable, or a sequence never sent, or wrong channels
  std::uint64_t foreign_datagrams = 0;        // datagrams from another address or port than the controller's
  std::uint64_t unauthenticated_replies = 0;  // version 2: a tag not made with the key
  std::uint64_t other_session_replies = 0;    // version 2: a genuine reply of another session (a replay)
  std::uint64_t send_errors = 0;
  std::uint64_t receive_errors = 0;
  std::uint64_t controller_faults = 0;  // replies with status kFault
};

class UdpControllerActuator final : public servo::Actuator, public ActuatorLinkReport {
 public:
  // Validates the config and binds the local socket (throws std::invalid_argument or
  // std::runtime_error). Not real-time safe.
  explicit UdpControllerActuator(const UdpControllerParameters& config);

  int channels() const override { return config_.channels; }

  // Begins a session, retrying until start_timeout_s: version 2 draws a new node nonce and
  // sends a hello, whose reply brings the controller's nonce; version 1 sends a query. Throws
  // std::runtime_error when the controller does not answer, reports a fault, has another
  // channel count, or measures farther than start_tolerance_m from initial_displacement_m.
  // Clears a latched fault. Not real-time safe.
  void start(std::span<const double> initial_displacement_m) override;

  // Sends the command and waits up to period_s + reply_timeout_s for its reply, draining
  // and counting stale ones. kNoReply on a missing reply; kFault, latched until start(),
  // after more than max_missed_replies in a row; kFault (not latched) when the controller
  // reports one. Real-time safe: no allocation.
  servo::ActuatorStatus exchange(std::span<const double> command_m, double period_s,
                                 servo::ActuatorReading& reading) override;

  std::string_view fault_text() const noexcept override { return fault_text_; }
  const UdpControllerCounters& counters() const { return counters_; }
  std::string_view summary_key() const override { return "udp_link"; }
  std::string describe_link() const override;
  nlohmann::json link_summary() const override;
  std::uint16_t local_port() const { return socket_.local_port(); }
  const Ipv4Endpoint& controller() const { return controller_; }

 private:
  // Takes every queued datagram; true (and `reply`) when one answers `sequence`.
  bool take_queued(std::uint64_t sequence, udp_protocol::ControllerReply& reply) noexcept;
  // take_queued, waiting until the monotonic deadline.
  bool await(std::uint64_t sequence, double deadline_s, udp_protocol::ControllerReply& reply) noexcept;
  // Encodes the command into the packet of the link's version.
  bool encode(const udp_protocol::ControllerCommand& command) noexcept;
  // Decodes a reply of the link's version and checks its session (counted when refused).
  bool decode(std::span<const std::byte> bytes, udp_protocol::ControllerReply& reply) noexcept;
  // Sends the encoded packet; counts it or the error.
  bool send_packet() noexcept;

  UdpControllerParameters config_;
  Ipv4Endpoint controller_;
  UdpSocket socket_;
  UdpControllerCounters counters_;
  std::unique_ptr<UdpAuthenticator> key_;  // version 2
  udp_protocol::Session session_;
  bool awaiting_hello_ = false;          // start(): the controller's nonce is not known yet
  udp_protocol::Session reply_session_;  // the session of the reply take_queued() matched
  udp_protocol::CommandPacket command_packet_{};
  udp_protocol::CommandPacketV2 command_packet_v2_{};
  std::array<std::byte, udp_protocol::kReplyBytesV2 + 1> receive_buffer_{};  // +1: oversized datagrams show
  std::uint64_t sequence_ = 0;
  int consecutive_missed_ = 0;
  bool link_fault_ = false;
  std::string_view fault_text_;  // a literal: set on the control path without allocation
};

// One line for a node's start: the controller, the protocol and, for version 1, that nothing
// on the link is authenticated.
std::string describe_link(const UdpControllerParameters& config);

}  // namespace rpsd::node
