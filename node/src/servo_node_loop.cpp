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
  h.serving_run_id = controller.serving_run();
  if (controller.faulted()) h.fault_text = controller.fault_text();
  // The actuator's newest reading, in every state: at rest, a coordinator calibrates from it.
  h.measured = controller.has_measurement();
  if (h.measured) {
    const servo::ActuatorReading& r = controller.latest_measurement();
    for (int c = 0; c < controller.config().channels; ++c) {
      h.displacement_m[c] = r.displacement_m[c];
      h.force_n[c] = r.force_n[c];
    }
  }
  return h;
}

// The loop wakes at least this often whatever the control period.
constexpr std::int64_t kWakeNs = 50'000'000;

// The control period in ns, within what the deadline arithmetic can add without overflow (a
// node's watchdog bound keeps a valid period far below it).
std::int64_t period_in_ns(double period_s) {
  const double ns = period_s * 1e9;
  return ns >= 1e15 ? static_cast<std::int64_t>(1e15) : std::max<std::int64_t>(1, std::llround(ns));
}

// Sleeps until `until_ns`, waking every kWakeNs to look at `stop`; false when it was set.
bool sleep_unless_stopped(std::int64_t until_ns, const std::atomic<bool>& stop) {
  while (!stop.load(std::memory_order_relaxed)) {
    const std::int64_t now = realtime::monotonic_now_ns();
    if (now >= until_ns) return true;
    realtime::sleep_until_ns(std::min(until_ns, now + kWakeNs));
  }
  return false;
}

}  // namespace

ServoNodeLoopReport run_servo_node_loop(ServoNodeController& controller, transport::DdsNodeEndpoint& endpoint,
                                        const ServoNodeLoopOptions& options, const std::atomic<bool>& stop) {
  ServoNodeLoopReport report;
  report.granted = realtime::apply_realtime(options.realtime);
  // Both modes: a real-time node wakes for every command, and a lock-step one answers on
  // Cyclone's receive thread, woken for every command too.
  const realtime::CpuWakeLatencyHold awake = realtime::hold_cpus_awake(options.realtime, report.granted);
  const std::int64_t period_ns = period_in_ns(controller.config().control_period_s);
  const std::int64_t start_ns = realtime::monotonic_now_ns();
  const std::int64_t end_ns =
      options.duration_s > 0.0 ? start_ns + static_cast<std::int64_t>(options.duration_s * 1e9) : 0;
  const auto release_after_ns = static_cast<std::int64_t>(options.release_after_silence_s * 1e9);
  realtime::LatencyHistogram jitter;
  TickWatch watch{controller, report};
  transport::CommandSample command;
  transport::FeedbackSample feedback;
  std::int64_t next_heartbeat_ns = start_ns;
  std::int64_t last_run_command_ns = start_ns;

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
  // Taking or leaving a run is announced at once: a coordinator that starts now must not read
  // an old heartbeat's word on what the node serves.
  const auto announce_if_changed = [&](std::uint64_t served_before, std::int64_t now_ns) {
    if (controller.serving_run() == served_before) return;
    next_heartbeat_ns = now_ns;
    maybe_heartbeat(now_ns);
  };
  const auto accept = [&](std::int64_t now_ns) {
    if (controller.accept(command) == CommandVerdict::kAccepted) last_run_command_ns = now_ns;
  };
  // Between ticks: the heartbeat, and a run whose coordinator fell silent frees the node.
  bool fault_announced = false;
  const auto between_ticks = [&](std::int64_t now_ns) {
    const std::uint64_t served = controller.serving_run();
    if (served != 0 && now_ns - last_run_command_ns > release_after_ns) controller.release_run();
    announce_if_changed(served, now_ns);
    // A fault is announced at once too: the coordinator that stops on it reports what it was.
    if (controller.faulted() && !fault_announced) {
      fault_announced = true;
      next_heartbeat_ns = now_ns;
    }
    maybe_heartbeat(now_ns);
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
      const std::int64_t now = realtime::monotonic_now_ns();
      if (end_ns > 0 && now >= end_ns) break;
      const bool command_came = endpoint.wait_for_command_until(std::min(deadline, now + kWakeNs));
      std::int64_t woke = realtime::monotonic_now_ns();
      if (!command_came && woke < deadline) {
        between_ticks(woke);  // a slow control rate: woken to look around, not to tick
        continue;
      }
      if (command_came && woke < last_tick + min_spacing_ns) {
        if (!sleep_unless_stopped(last_tick + min_spacing_ns, stop)) break;
        woke = realtime::monotonic_now_ns();
      }
      last_tick = woke;
      if (!command_came) {
        jitter.add(woke - deadline);
        if (woke - deadline >= period_ns) ++report.late_wakeups;
      }
      const std::uint64_t served = controller.serving_run();
      while (endpoint.take_command(command)) accept(woke);
      controller.tick(feedback);
      watch.after_tick();
      publish();
      ++report.cycles;
      const std::int64_t done = realtime::monotonic_now_ns();
      // A tick woken late (this host stalled the node) is not followed by catch-up ticks: ticks
      // without a command stay 3/4 of a period apart, so the watchdog counts real time without
      // commands, not the node's own stall (commands queued meanwhile are taken at the next tick).
      deadline = command_came ? woke + period_ns + grace_ns : std::max(deadline + period_ns, woke + min_spacing_ns);
      if (done > deadline) {
        // The tick itself took longer than a period: count it and re-anchor.
        ++report.overruns;
        deadline = done + period_ns;
      }
      announce_if_changed(served, done);
      between_ticks(done);
    }
    report.jitter = jitter.summary();
  } else {
    // Lock-step: each command is answered on Cyclone's receive thread as it arrives, so no
    // other thread has to be woken for it (the round trip loses one thread hand-off). This
    // thread sends the heartbeats, watches the stop flag and frees the node from a silent
    // run; the mutex keeps the two apart.
    std::mutex mutex;
    const auto answer = [&] {
      const std::lock_guard lock(mutex);
      const std::uint64_t served = controller.serving_run();
      const std::int64_t now = realtime::monotonic_now_ns();
      while (endpoint.take_command(command)) {
        const CommandVerdict verdict = controller.accept(command);
        // The run's own command repeated (its coordinator held by an operator, rpsd stop
        // --hold): the run is alive, and nothing is applied a second time.
        if (verdict == CommandVerdict::kNotNewer && command.run_id == controller.serving_run()) {
          last_run_command_ns = now;
          continue;
        }
        if (verdict != CommandVerdict::kAccepted) continue;
        controller.tick(feedback);
        last_run_command_ns = now;
        watch.after_tick();
        publish();
      }
      announce_if_changed(served, now);
    };
    using Answer = decltype(answer);
    endpoint.call_on_command_arrival([](void* a) { (*static_cast<const Answer*>(a))(); },
                                     const_cast<void*>(static_cast<const void*>(&answer)));
    answer();  // any command that came before the listener was in place
    while (!stop.load(std::memory_order_relaxed)) {
      const std::int64_t now = realtime::monotonic_now_ns();
      {
        const std::lock_guard lock(mutex);
        between_ticks(now);
      }
      if (end_ns > 0 && now >= end_ns) break;
      // Wake at least every 50 ms to look at the stop flag, and for the next heartbeat.
      realtime::sleep_until_ns(std::min(now + kWakeNs, next_heartbeat_ns));
    }
    endpoint.call_on_command_arrival(nullptr, nullptr);
  }
  return report;
}

}  // namespace rpsd::node
