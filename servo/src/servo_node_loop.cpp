#include "rpsd/servo/servo_node_loop.h"

#include <cmath>

#include "rpsd/realtime/pacer.h"

namespace rpsd::servo {
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
      report.last_command_tick = tick;
      report.hold_tick = -1;
    } else if (controller.holding() && report.hold_tick < 0 && report.last_command_tick >= 0) {
      report.hold_tick = tick;
    }
    if (controller.faulted() && report.faulted_tick < 0) report.faulted_tick = tick;
    ++tick;
  }
};

transport::NodeHeartbeat heartbeat(const ServoNodeController& controller, const ServoNodeLoopReport& report, std::int64_t ticks) {
  transport::NodeHeartbeat h;
  h.test_id = controller.config().test_id;
  h.site_id = controller.config().site_id;
  h.channels = static_cast<std::uint8_t>(controller.config().channels);
  h.state = controller.faulted()   ? transport::NodeHeartbeat::kFaulted
            : controller.holding() ? transport::NodeHeartbeat::kHolding
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
  const double period_s = controller.config().control_period_s;
  const auto period_ns = static_cast<std::int64_t>(std::llround(period_s * 1e9));
  const auto heartbeat_every = std::max<std::int64_t>(1, std::llround(1.0 / (options.heartbeat_rate_hz * period_s)));
  const std::int64_t start_ns = realtime::monotonic_now_ns();
  const std::int64_t end_ns = options.duration_s > 0.0 ? start_ns + static_cast<std::int64_t>(options.duration_s * 1e9) : 0;
  realtime::Pacer pacer(period_ns);
  realtime::LatencyHistogram jitter;
  TickWatch watch{controller, report};
  transport::CommandSample command;
  transport::FeedbackSample feedback;
  std::int64_t next_heartbeat_ns = start_ns;

  const auto publish = [&] {
    if (endpoint.publish(feedback)) ++report.feedback_published;
    else ++report.publish_failures;
  };
  const auto maybe_heartbeat = [&](std::int64_t now_ns) {
    if (now_ns < next_heartbeat_ns) return;
    endpoint.publish_heartbeat(heartbeat(controller, report, watch.tick));
    next_heartbeat_ns = now_ns + static_cast<std::int64_t>(1e9 / options.heartbeat_rate_hz);
  };

  if (options.real_time) {
    pacer.start();
    while (!stop.load(std::memory_order_relaxed)) {
      jitter.add(pacer.wait_next());
      while (endpoint.take_command(command)) controller.accept(command);
      controller.tick(feedback);
      watch.after_tick();
      publish();
      if (watch.tick % heartbeat_every == 0) maybe_heartbeat(realtime::monotonic_now_ns());
      if (end_ns > 0 && realtime::monotonic_now_ns() >= end_ns) break;
    }
    report.cycles = pacer.cycles();
    report.overruns = pacer.overruns();
    report.skipped_deadlines = pacer.skipped_deadlines();
    report.jitter = jitter.summary();
  } else {
    while (!stop.load(std::memory_order_relaxed)) {
      const std::int64_t now = realtime::monotonic_now_ns();
      maybe_heartbeat(now);
      if (end_ns > 0 && now >= end_ns) break;
      // Wake at least every 50 ms to look at the stop flag and send heartbeats.
      if (!endpoint.wait_for_command_until(now + 50'000'000)) continue;
      while (endpoint.take_command(command)) {
        if (controller.accept(command) != CommandVerdict::kAccepted) continue;
        controller.tick(feedback);
        watch.after_tick();
        publish();
      }
    }
  }
  return report;
}

}  // namespace rpsd::servo
