// The messages between the coordinator and a servo node: fixed size, so that neither side
// allocates per message and the same layout maps onto @final DDS types.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace rpsd::transport {

inline constexpr int kMaxChannels = 8;
// Room for a node's fault in its heartbeat (NodeHeartbeat::fault_text).
inline constexpr std::size_t kFaultTextBytes = 160;

// How a channel's actuator is driven (CommandSample::control_mode): it follows the command's
// displacement, or holds its force (mixed control, issue 30). A node refuses a command whose
// mode differs from the one its node file declares for the channel.
enum ControlMode : std::uint8_t {
  kDisplacementControl = 0,
  kForceControl = 1,
};

// Commands for one control step: per channel a displacement, or a force for a channel in force
// control. Every channel is in displacement control unless its control_mode says otherwise.
struct CommandSample {
  std::uint32_t test_id = 0;
  std::uint32_t site_id = 0;
  // The coordinator's run (draw_run_id, never 0): a node serves one run at a time.
  std::uint64_t run_id = 0;
  std::int64_t step = 0;
  double time_s = 0.0;
  double control_period_s = 0.0;  // the coordinator's; 0: not stated (in process)
  bool end_of_run = false;        // the run is over; no displacement: the node is free again
  std::uint8_t channels = 0;
  std::array<double, kMaxChannels> displacement_m{};
  std::array<std::uint8_t, kMaxChannels> control_mode{};  // ControlMode; 0: displacement
  std::array<double, kMaxChannels> force_n{};             // the force held by a force channel
  // Filled by the node's endpoint, never sent: the DDS writer that sent the command (its
  // instance handle; 0 in process). A node follows one writer of its run.
  std::uint64_t writer = 0;
};

// Node status bits reported with every feedback sample.
enum NodeStatus : std::uint32_t {
  kNodeOk = 0,
  kNodeLimitActive = 1u << 0,     // a limit changed the command or the state this period
  kNodeFault = 1u << 1,           // the node cannot follow commands (bad command, aborted, hardware)
  kNodeHolding = 1u << 2,         // commands stopped arriving: the node holds (or ramps to safe)
  kNodeEndStop = 1u << 3,         // a piston is at the end of its stroke
  kNodeValveSaturated = 1u << 4,  // a servovalve is fully open: the actuator cannot go faster
};

// Which limit acted (FeedbackSample::limit_flags); the node's limits are its own, whatever
// the coordinator sends.
enum LimitFlag : std::uint32_t {
  kLimitNone = 0,
  kLimitStroke = 1u << 0,
  kLimitVelocity = 1u << 1,
  kLimitForce = 1u << 2,
  kLimitIncrement = 1u << 3,
  kLimitAcceleration = 1u << 4,
};

// What the node measured at the end of the control step the command belongs to.
struct FeedbackSample {
  std::uint32_t test_id = 0;
  std::uint32_t site_id = 0;
  std::uint64_t run_id = 0;  // the run the node serves (0: none); only that run may use it
  std::int64_t step = 0;
  double time_s = 0.0;
  std::uint8_t channels = 0;
  std::array<double, kMaxChannels> displacement_m{};
  std::array<double, kMaxChannels> force_n{};
  std::uint32_t status = kNodeOk;
  std::uint32_t limit_flags = kLimitNone;
  // Filled by the coordinator's link, never sent: command-to-feedback time of the channel's
  // site for this step (0 in process).
  std::array<std::int64_t, kMaxChannels> round_trip_ns{};
};

// Copies the fields of a command that are not per channel (its test, run, step, time, end of
// run, writer) and names the site and its channel count, for a link that fills a site's
// channels itself. Real-time safe.
inline void copy_command_header(const CommandSample& from, CommandSample& to, std::uint32_t site_id,
                                std::uint8_t channels) {
  // A new field of CommandSample changes its size: copy it here too, then update the size.
  static_assert(sizeof(CommandSample) == 192, "copy_command_header: copy the new field of CommandSample");
  to.test_id = from.test_id;
  to.site_id = site_id;
  to.run_id = from.run_id;
  to.step = from.step;
  to.time_s = from.time_s;
  to.control_period_s = from.control_period_s;
  to.end_of_run = from.end_of_run;
  to.channels = channels;
  to.writer = from.writer;
}

// True when the measured displacement or force of one of the first `channels` channels is
// not a finite number: a failed transducer, which must stop a test.
inline bool has_non_finite_measurement(const FeedbackSample& sample, int channels) {
  for (int c = 0; c < channels; ++c) {
    if (!std::isfinite(sample.displacement_m[c]) || !std::isfinite(sample.force_n[c])) return true;
  }
  return false;
}

// A node's periodic announcement: lets the coordinator discover the sites of its test.
struct NodeHeartbeat {
  enum State : std::uint32_t { kWaiting = 0, kRunning = 1, kHolding = 2, kFaulted = 3 };
  std::uint32_t test_id = 0;
  std::uint32_t site_id = 0;
  std::uint8_t channels = 0;
  std::uint32_t state = kWaiting;
  std::int64_t ticks = 0;
  std::int64_t overruns = 0;
  std::int64_t dropped_messages = 0;
  double control_period_s = 0.0;
  // The node's command reader and feedback writer have both matched a coordinator's (DDS
  // discovery done on the node's side too). Filled in by DdsNodeEndpoint::publish_heartbeat.
  bool coordinator_matched = false;
  std::uint64_t serving_run_id = 0;  // the run the node serves (0: none)
  // kFaulted: what faulted the node (the lab controller's own words when it gave any),
  // NUL-terminated and cut to fit; empty otherwise.
  std::array<char, kFaultTextBytes> fault_text{};
  // Each channel's newest measured displacement and force (issue 30: a coordinator calibrates
  // a setup's actuators from them at rest, before its first command). measured false: the node
  // has not read its actuator yet (hardware in lock-step before its first command), and the
  // values mean nothing.
  bool measured = false;
  std::array<double, kMaxChannels> displacement_m{};
  std::array<double, kMaxChannels> force_n{};
};

// A new run's identity: 64 random bits from std::random_device, never 0 (which means no run).
// Not real-time safe.
std::uint64_t draw_run_id();
// A run id as 16 hex digits, for messages.
std::string run_id_text(std::uint64_t run_id);

}  // namespace rpsd::transport
