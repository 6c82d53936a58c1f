// A lab site in software: it serves the NEES/LabVIEW plugin protocol as OpenFresco's ECLabVIEW
// client expects it to (docs/lab-controllers.md), with simulated plants behind its
// control points. Its parsing is its own, written from OpenFresco's client, not rpsd's
// encoder, so that the node's adapter is tested against the protocol and not against itself.
// One session at a time, from its node's address only; a proposal beyond a control point's
// limits is refused in the site's words; an executed proposal is reached over
// step_duration_s. Tests make it misbehave on purpose (fault). Not real-time safe.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/node/tcp_stream.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::node {

// One axis of a control point, one simulated actuator behind it.
struct PluginSiteDof {
  std::string axis = "x";              // x, y or z
  std::string motion = "translation";  // translation (displacement, force) or rotation (rotation, moment)
  double lower_limit = -1.0;           // what the site accepts, in its own units
  double upper_limit = 1.0;
  double displacement_per_si = 1.0;  // the site's units per m (per rad)
  double force_per_si = 1.0;         // per N (per N m)
};

struct PluginSiteControlPoint {
  std::string name;
  std::vector<PluginSiteDof> dofs;
};

// Misbehaviour on purpose, for tests and rehearsals of a failure.
enum class PluginSiteFault : std::uint8_t {
  kNone,
  kStopAnswering,     // reads every request from the next proposal on and answers none
  kGarbage,           // answers get-control-point with values that are no numbers
  kOverlong,          // answers get-control-point with a line of 64 KiB
  kWrongTransaction,  // answers get-control-point with another transaction
};

struct PluginSiteConfig {
  std::string bind_host = "127.0.0.1";  // dotted IPv4
  std::uint16_t port = 0;               // 0: any free port (PluginSiteEmulator::port())
  std::string node_host = "127.0.0.1";  // the one address it serves
  double step_duration_s = 0.05;        // an executed proposal is reached over this long
  std::vector<PluginSiteControlPoint> control_points;
  PluginSiteFault fault = PluginSiteFault::kNone;
  long fault_after_steps = 0;  // steps executed normally before the fault

  int channels() const;  // the dofs of every control point, in order
  // The keys of a plugin_site section; each dof's section goes to `dof_sections`, for check().
  // Not real-time safe.
  static PluginSiteConfig read(config::Source& site, std::vector<std::unique_ptr<config::Source>>& dof_sections);
  // Then, once every key of the file is read (so that a listing of the keys has seen them
  // all): the limits, the dof count and the addresses, failing at the key.
  void check(config::Source& site, std::vector<std::unique_ptr<config::Source>>& dof_sections) const;
};

struct PluginSiteCounters {
  std::uint64_t connections = 0;        // clients served
  std::uint64_t sessions = 0;           // open-session taken
  std::uint64_t refused_clients = 0;    // a second client while one is served: an error line, closed
  std::uint64_t foreign_clients = 0;    // a client from another address than the node's: the same
  std::uint64_t requests = 0;           // lines read
  std::uint64_t proposals = 0;          // proposals taken
  std::uint64_t refused_proposals = 0;  // beyond a limit, or naming what the site does not have
  std::uint64_t executes = 0;           // steps executed
  std::uint64_t readings = 0;           // control point lines answered
  std::uint64_t bad_requests = 0;       // unknown, malformed, out of order, overlong
  std::uint64_t unanswered = 0;         // requests left unanswered on purpose (fault)
  std::uint64_t closed_sessions = 0;    // close-session taken
  std::uint64_t disconnects = 0;        // a client that left without close-session
};

class PluginSiteEmulator {
 public:
  enum class Served : std::uint8_t { kAccepted, kRefusedClient, kAnswered, kClosed, kTimeout, kStopped };

  // `plants` (one per dof, not owned) must outlive the emulator. Listens. Throws
  // std::invalid_argument (a bad address, a plant count that is not the dofs') or
  // std::runtime_error. Not real-time safe.
  PluginSiteEmulator(std::span<servo::Plant* const> plants, const PluginSiteConfig& config);

  std::uint16_t port() const { return listener_.port(); }
  int channels() const { return actuator_.channels(); }
  const PluginSiteConfig& config() const { return config_; }

  // Puts the plants at rest at these displacements (SI, one per dof). Call before serving.
  void start(std::span<const double> initial_displacement_m);

  // Handles one event (a client arriving, one request line), waiting at most timeout_s;
  // returns within 50 ms of request_stop().
  Served serve(double timeout_s);

  void request_stop() noexcept { stop_.store(true); }
  const PluginSiteCounters& counters() const { return counters_; }
  const servo::ActuatorReading& reading() const { return reading_; }
  // The last refusal's line, for the summary.
  const std::string& last_refusal() const { return last_refusal_; }

 private:
  void answer(const std::string& line);
  void refuse_client(TcpStream& client, const std::string& why);
  void handle(const std::string& line);
  void propose(const std::vector<std::string>& fields);
  void execute(const std::vector<std::string>& fields);
  void get_control_point(const std::vector<std::string>& fields);
  void refuse(const std::string& transaction, const std::string& why);
  bool faulty() const;

  PluginSiteConfig config_;
  servo::SimulatedActuator actuator_;
  TcpListener listener_;
  std::array<std::uint8_t, 4> node_address_{};
  std::optional<TcpStream> session_;
  bool opened_ = false;
  bool silent_ = false;              // PluginSiteFault::kStopAnswering has begun
  std::string proposed_, executed_;  // transactions
  std::vector<double> proposed_m_, command_m_;
  servo::ActuatorReading reading_;
  PluginSiteCounters counters_;
  std::string last_refusal_;
  std::vector<char> line_;
  std::atomic<bool> stop_{false};
};

}  // namespace rpsd::node
