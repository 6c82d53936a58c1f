// The servo node's control loop around its controller and its DDS endpoint (the pattern of
// ros2_control_node: lock memory, raise priority, absolute deadlines, count overruns).
// Real time: ticks on its own deadlines, applies each command on the tick it triggers and holds after
// command_timeout_periods without one. Lock-step: one tick per command, answered on Cyclone's receive
// thread, so the plant does not advance while the coordinator computes. Details: docs/realtime.md
// Either way the loop wakes at least every 50 ms (the stop flag, the duration, the heartbeat),
// whatever the control period, and frees the node from a run whose commands have stopped.
#pragma once

#include <atomic>
#include <cstdint>

#include "rpsd/node/servo_node_controller.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/realtime/realtime_setup.h"
#include "rpsd/transport/dds_node_endpoint.h"

namespace rpsd::node {

struct ServoNodeLoopOptions {
  bool real_time = true;
  double heartbeat_rate_hz = 10.0;
  realtime::RealTimeRequest realtime;
  // Stop after this long (0: until `stop` is set).
  double duration_s = 0.0;
  // A run that sends no command for this long has ended without saying so (its coordinator
  // died): the node frees itself for another. Longer than any pause of a live run (a host
  // stalled for a second or two), shorter than an operator takes to start the next run.
  double release_after_silence_s = 5.0;
};

struct ServoNodeLoopReport {
  realtime::RealTimeSetupReport granted;
  std::int64_t cycles = 0, overruns = 0;
  std::int64_t late_wakeups =
      0;  // ticks without a command woken a period or more after their deadline (a stalled host)
  realtime::LatencySummary jitter;       // wake-up lateness of the ticks made without a command
  std::int64_t first_command_tick = -1;  // tick on which the first command was applied
  std::int64_t last_command_tick = -1;   // tick on which the last command was applied
  std::int64_t hold_tick = -1;           // first tick the watchdog held after it (-1: never)
  std::int64_t faulted_tick = -1;        // first tick with a latched fault (-1: never)
  std::int64_t feedback_published = 0, publish_failures = 0;
};

// Runs until `stop` becomes true or the duration ends. The controller must be started.
// Not real-time safe to call; the loop inside is.
ServoNodeLoopReport run_servo_node_loop(ServoNodeController& controller, transport::DdsNodeEndpoint& endpoint,
                                        const ServoNodeLoopOptions& options, const std::atomic<bool>& stop);

}  // namespace rpsd::node
