#include "rpsd/node/servo_node_loop.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "rpsd/node/lock_step_node.h"
#include "rpsd/realtime/pacer.h"  // monotonic_now_ns

namespace rpsd::node {
namespace {

// Bookkeeping shared by both modes after each tick.
struct TickWatch {
  ServoNodeController& controller;
  ServoNodeLoopReport& report;
  std::uint64_t applied_before = 0;
  std::int64_t tick = 0;

  void after_tick() {
    const auto& c = controller.counters();
    if (c.applied != applied_before) {
      applied_before = c.applied;
      if (report.first_command_tick < 0) report.first_command_tick = tick;
      report.last_command_tick = tick;
      report.hold_tick = -1;
    } else if (controller.holding() && report.hold_tick < 0 && report.last_command_tick >= 0) {
      report.hold_tick = tick;
    }
    if (controller.faulted() && report.faulted_tick < 0) report.faulted_tick = tick;
    ++tick;
  }
};

transport::NodeHeartbeat heartbeat(const ServoNodeController& controller, const ServoNodeLoopReport& report,
                                   std::int64_t ticks) {
  transport::NodeHeartbeat h;
  h.test_id = controller.config().test_id;
  h.site_id = controller.config().site_id;
  h.channels = static_cast<std::uint8_t>(controller.config().channels);
  h.state = controller.faulted()            ? transport::NodeHeartbeat::kFaulted
            : controller.holding()          ? transport::NodeHeartbeat::kHolding
            : report.last_command_tick >= 0 ? transport::NodeHeartbeat::kRunning
                                            : transport::NodeHeartbeat::kWaiting;
  h.ticks = ticks;
  h.overruns = report.overruns;
  h.dropped_messages = static_cast<std::int64_t>(controller.counters().dropped_total());
  h.control_period_s = controller.config().control_period_s;
  return h;
}

}  // namespace

ServoNodeLoopReport run_servo_node_loop(ServoNodeController& controller, transport::DdsNodeEndpoint& endpoint,
                                        const ServoNodeLoopOptions& options, const std::atomic<bool>& stop) {
  ServoNodeLoopReport report;
  report.granted = realtime::apply_realtime(options.realtime);
  // Both modes: a real-time node wakes for every command, and a lock-step one answers on
  // Cyclone's receive thread, woken for every command too.
  const realtime::CpuWakeLatencyHold awake = realtime::hold_cpus_awake(options.realtime, report.granted);
  const double period_s = controller.config().control_period_s;
  const auto period_ns = static_cast<std::int64_t>(std::llround(period_s * 1e9));
  const std::int64_t start_ns = realtime::monotonic_now_ns();
  const std::int64_t end_ns =
      options.duration_s > 0.0 ? start_ns + static_cast<std::int64_t>(options.duration_s * 1e9) : 0;
  realtime::LatencyHistogram jitter;
  TickWatch watch{controller, report};
  transport::CommandSample command;
  transport::FeedbackSample feedback;
  std::int64_t next_heartbeat_ns = start_ns;

  const auto publish = [&] {
    if (endpoint.publish(feedback))
      ++report.feedback_published;
    else
      ++report.publish_failures;
  };
  const auto maybe_heartbeat = [&](std::int64_t now_ns) {
    if (now_ns < next_heartbeat_ns) return;
    endpoint.publish_heartbeat(heartbeat(controller, report, watch.tick));
    next_heartbeat_ns = now_ns + static_cast<std::int64_t>(1e9 / options.heartbeat_rate_hz);
  };

  if (options.real_time) {
    // Ticks are triggered by the commands: a command is applied the moment it arrives and
    // the next tick is due two periods after it (one period plus one of grace). When none comes, the node ticks on that
    // deadline anyway, one period apart, and after command_timeout_periods such ticks it holds. So the node follows the
    // coordinator's clock without a phase offset adding latency, and its watchdog runs on its own clock. A command may
    // come up to one period late before the node ticks without it (the coordinator's jitter on a loaded machine must
    // not advance the plant on its own), and ticks stay at least 3/4 of a period apart, so a command that arrives just
    // after a deadline tick waits instead of advancing the plant a second period.
    const std::int64_t grace_ns = period_ns;
    const std::int64_t min_spacing_ns = period_ns * 3 / 4;
    std::int64_t deadline = realtime::monotonic_now_ns() + period_ns + grace_ns;
    std::int64_t last_tick = 0;
    while (!stop.load(std::memory_order_relaxed)) {
      const bool command_came = endpoint.wait_for_command_until(deadline);
      std::int64_t woke = realtime::monotonic_now_ns();
      if (command_came && woke < last_tick + min_spacing_ns) {
        realtime::sleep_until_ns(last_tick + min_spacing_ns);
        woke = realtime::monotonic_now_ns();
      }
      last_tick = woke;
      if (!command_came) jitter.add(woke - deadline);
      while (endpoint.take_command(command)) controller.accept(command);
      controller.tick(feedback);
      watch.after_tick();
      publish();
      ++report.cycles;
      const std::int64_t done = realtime::monotonic_now_ns();
      deadline = command_came ? woke + period_ns + grace_ns : deadline + period_ns;
      if (done > deadline) {
        // The tick itself took longer than a period: count it and re-anchor.
        ++report.overruns;
        deadline = done + period_ns;
      }
      maybe_heartbeat(done);
      if (end_ns > 0 && done >= end_ns) break;
    }
    report.jitter = jitter.summary();
  } else {
    // Lock-step: each command is answered on Cyclone's receive thread as it arrives, so no
    // other thread has to be woken for it (the round trip loses one thread hand-off). This
    // thread sends the heartbeats and watches the stop flag; the mutex keeps the two apart.
    std::mutex mutex;
    const auto answer = [&] {
      const std::lock_guard lock(mutex);
      while (endpoint.take_command(command)) {
        if (!answer_lock_step(controller, command, feedback)) continue;
        watch.after_tick();
        publish();
      }
    };
    using Answer = decltype(answer);
    endpoint.call_on_command_arrival([](void* a) { (*static_cast<const Answer*>(a))(); },
                                     const_cast<void*>(static_cast<const void*>(&answer)));
    answer();  // any command that came before the listener was in place
    while (!stop.load(std::memory_order_relaxed)) {
      const std::int64_t now = realtime::monotonic_now_ns();
      {
        const std::lock_guard lock(mutex);
        maybe_heartbeat(now);
      }
      if (end_ns > 0 && now >= end_ns) break;
      // Wake at least every 50 ms to look at the stop flag, and for the next heartbeat.
      realtime::sleep_until_ns(std::min(now + 50'000'000, next_heartbeat_ns));
    }
    endpoint.call_on_command_arrival(nullptr, nullptr);
  }
  return report;
}

}  // namespace rpsd::node
