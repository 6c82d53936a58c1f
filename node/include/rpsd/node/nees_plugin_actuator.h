// Hardware adapter: a lab site that serves the NEES/LabVIEW plugin protocol (a LabVIEW
// program, UIUC's load and boundary condition boxes, MiniMOST), driven as OpenFresco's
// ECLabVIEW drives it (docs/lab-controllers.md). Each control period proposes the
// command under a new transaction, executes it and reads every control point, over one TCP
// connection to the one configured site, all within period_s + reply_timeout_s. A refusal,
// a late, malformed or oversized answer, or a closed connection latches kFault: a text
// protocol cannot resume mid-transaction, so the link is given up and the site's words are
// kept for summary.json.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/node/actuator_link_report.h"
#include "rpsd/node/nees_plugin_messages.h"
#include "rpsd/node/tcp_stream.h"
#include "rpsd/servo/actuator.h"
#include "rpsd/servo/envelope.h"

namespace rpsd::node {

struct OwnedActuator;

// One channel's place at the site.
struct NeesPluginChannel {
  std::string control_point;  // the site's name for it ("MDL-00-01")
  nees_plugin::Axis axis = nees_plugin::Axis::kX;
  nees_plugin::Motion motion = nees_plugin::Motion::kTranslation;
  double displacement_per_si = 1.0;  // the site's unit of displacement per m (of rotation per rad)
  double force_per_si = 1.0;         // the site's unit of force per N (of moment per N m)
};

struct NeesPluginParameters {
  static constexpr std::string_view kName = "nees_plugin";
  static constexpr std::string_view kSummary =
      "a NEES/LabVIEW plugin site, OpenFresco's ECLabVIEW protocol over TCP (docs/lab-controllers.md)";
  static NeesPluginParameters read(config::Source& section, int channels);
  static OwnedActuator make(const NeesPluginParameters& config, int channels);
  servo::Envelope envelope() const { return rig; }
  // Why a channel cannot be in `mode` (empty: it can): the protocol has no force command.
  std::string control_mode_refusal(int /*channel*/, servo::ControlMode mode) const {
    return mode == servo::ControlMode::kForce ? "the NEES plugin protocol's propose and execute messages carry "
                                                "displacements and rotations only, no force command"
                                              : "";
  }

  int channels = 1;
  std::string host = "127.0.0.1";  // the site (dotted IPv4): the only peer the node talks to
  std::uint16_t port = 0;
  std::string local_host = "0.0.0.0";       // the node's side of the connection
  std::uint16_t local_port = 0;             // 0: any (a site that filters needs a fixed one)
  std::string session_name = "OpenFresco";  // open-session and close-session, as OpenFresco names it
  // One set-parameter line each, its fields in order; OpenFresco's own by default.
  std::vector<std::vector<std::string>> parameters{{"OPFTransaction", "nstep", "1"}};
  std::vector<NeesPluginChannel> channel_map;  // one per channel
  // How long past the control period a whole step (propose, execute, read) may take: a site
  // reaches its target over seconds in a slow test.
  double reply_timeout_s = 30.0;
  double connect_timeout_s = 10.0;
  double start_tolerance_m = 1e-3;    // start(): largest |measured - initial| of a translation
  double start_tolerance_rad = 1e-3;  // and of a rotation
  servo::Envelope rig;                // what the rig can do; required

  // Throws std::invalid_argument naming the field. Not real-time safe.
  void validate() const;
};

struct NeesPluginCounters {
  std::uint64_t proposals = 0;      // propose lines sent
  std::uint64_t executes = 0;       // execute lines sent
  std::uint64_t readings = 0;       // control point answers taken
  std::uint64_t refusals = 0;       // answers whose first field is not OK
  std::uint64_t timeouts = 0;       // a step not answered in time
  std::uint64_t malformed = 0;      // answers of another transaction or control point, cut short, unparsable
  std::uint64_t overlong = 0;       // answers longer than nees_plugin::kMaxLineBytes
  std::uint64_t closed = 0;         // the site closed the connection
  std::uint64_t node_failures = 0;  // a command the node could not send (not finite, a socket error)
};

// Why the link failed, once it has.
enum class NeesPluginFailure : std::uint8_t {
  kNone,
  kRefused,
  kTimeout,
  kClosed,
  kMalformed,
  kWrongTransaction,
  kWrongControlPoint,
  kMissingChannel,
  kOverlong,
  kNodeSide,  // the node could not write or send its line
};
const char* failure_name(NeesPluginFailure failure) noexcept;

class NeesPluginActuator final : public servo::Actuator, public ActuatorLinkReport {
 public:
  // Validates the config; connects only in start(). Not real-time safe.
  explicit NeesPluginActuator(const NeesPluginParameters& config);
  // Ends the session (close-session, waiting at most kCloseTimeoutS for its answer).
  ~NeesPluginActuator() override;
  NeesPluginActuator(const NeesPluginActuator&) = delete;
  NeesPluginActuator& operator=(const NeesPluginActuator&) = delete;

  static constexpr double kCloseTimeoutS = 2.0;

  int channels() const override { return config_.channels; }

  // Connects (connect_timeout_s), opens the session and sets the parameters, then proposes
  // the initial displacement (no motion for a rig where the node expects it), executes it and
  // reads the control points, as OpenFresco's setup() does. Throws std::runtime_error with the
  // site's own words when it refuses, or when a channel measures farther than the start
  // tolerance from its initial displacement. Not real-time safe.
  void start(std::span<const double> initial_displacement_m) override;

  // Propose, execute, get-control-point within period_s + reply_timeout_s. kFault, latched
  // until start(), on any failure (failure(), site_message()). Real-time safe: no allocation.
  servo::ActuatorStatus exchange(std::span<const double> command_m, double period_s,
                                 servo::ActuatorReading& reading) override;

  const NeesPluginCounters& counters() const { return counters_; }
  // After a fault: "plugin site refused at propose: <the site's line>". Real-time safe.
  std::string_view fault_text() const noexcept override { return fault_text_.data(); }
  NeesPluginFailure failure() const { return failure_; }
  // "site" (refused, late, malformed, closed), "node" or "none".
  std::string_view failed_side() const;
  // The line the site answered when the link failed (refused or malformed), bounded.
  std::string_view site_message() const { return {site_message_.data(), site_message_size_}; }
  const servo::ActuatorReading& initial_reading() const { return initial_; }
  std::uint16_t local_port() const { return stream_ ? stream_->local_port() : 0; }

  std::string_view summary_key() const override { return "plugin_link"; }
  std::string describe_link() const override;
  nlohmann::json link_summary() const override;

 private:
  enum class Stage : std::uint8_t { kNone, kOpenSession, kSetParameter, kPropose, kExecute, kGetControlPoint };
  static const char* stage_name(Stage stage) noexcept;
  // Sends writer_'s line and takes one answer line into line_ before the deadline.
  bool request(Stage stage, double deadline_s) noexcept;
  bool send(Stage stage, double deadline_s) noexcept;
  bool receive(Stage stage, double deadline_s) noexcept;
  // The step: propose `command_m`, execute, read every control point into `reading`.
  bool transact(std::span<const double> command_m, double deadline_s, servo::ActuatorReading& reading) noexcept;
  bool read_control_point(std::size_t point, double deadline_s, servo::ActuatorReading& reading) noexcept;
  // Latches the failure; keeps line_ as the site's words when `keep_line`.
  bool fail(NeesPluginFailure failure, Stage stage, bool keep_line) noexcept;
  void send_close_session() noexcept;
  [[noreturn]] void throw_start_failure(const std::string& what) const;

  NeesPluginParameters config_;
  Ipv4Endpoint site_, local_;
  std::vector<std::string> control_points_;        // distinct names, in order of first use
  std::vector<nees_plugin::ChannelPoint> points_;  // one per channel
  std::optional<TcpStream> stream_;
  nees_plugin::TransactionIds ids_;
  nees_plugin::LineWriter writer_;
  std::array<char, nees_plugin::kMaxLineBytes> line_{};
  std::size_t line_size_ = 0;
  std::array<double, servo::kMaxChannels> site_values_{};  // the command in the site's units
  std::array<bool, 2 * servo::kMaxChannels> seen_{};       // the answer's values taken this step
  NeesPluginCounters counters_;
  bool link_fault_ = false;
  NeesPluginFailure failure_ = NeesPluginFailure::kNone;
  Stage failed_stage_ = Stage::kNone;
  static constexpr std::size_t kSiteMessageBytes = 256;
  std::array<char, kSiteMessageBytes> site_message_{};
  std::size_t site_message_size_ = 0;
  bool site_message_cut_ = false;
  std::array<char, 160> fault_text_{};
  std::array<char, 48> failed_transaction_{};
  std::size_t failed_transaction_size_ = 0;
  std::uint64_t steps_ = 0;  // transactions executed and read
  servo::ActuatorReading initial_;
};

}  // namespace rpsd::node
