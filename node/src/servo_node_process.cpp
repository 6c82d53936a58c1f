#include "rpsd/node/servo_node_process.h"

#include <ostream>
#include <string>
#include <vector>

#include "rpsd/node/controller_emulator.h"
#include "rpsd/node/servo_node_loop.h"
#include "rpsd/realtime/latency_json.h"
#include "rpsd/realtime/pacer.h"

namespace rpsd::node {
namespace {

nlohmann::json node_summary(const ServoNodeSetup& setup, const ServoNodeController& controller,
                            const ServoNodeLoopReport& report) {
  using nlohmann::json;
  const auto& c = controller.counters();
  json dropped = json::object();
  for (int v = 1; v < kCommandVerdicts; ++v) {
    if (v == static_cast<int>(CommandVerdict::kEndOfRun)) continue;  // not a drop
    dropped[command_verdict_name(static_cast<CommandVerdict>(v))] = c.by_verdict[v];
  }
  json run_events = json::array();
  for (const auto& e : controller.run_events()) {
    json event = {{"event", run_event_name(e.kind)},
                  {"tick", e.tick},
                  {"run_id", transport::run_id_text(e.run_id)},
                  {"writer", e.writer},
                  {"step", e.step}};
    if (e.kind == RunEvent::Kind::kRefused) {
      event["reason"] = command_verdict_name(e.verdict);
      event["serving_run_id"] = e.serving_run_id != 0 ? json(transport::run_id_text(e.serving_run_id)) : json(nullptr);
    }
    run_events.push_back(event);
  }
  json limits = json::object();
  for (int k = 0; k < kLimitKinds; ++k) {
    limits[limit_kind_name(static_cast<LimitKind>(k))] = {{"activations", c.limit_activations[k]},
                                                          {"active_ticks", c.limit_active_ticks[k]}};
  }
  json events = json::array();
  for (const auto& e : controller.events()) {
    events.push_back({{"tick", e.tick},
                      {"step", e.step},
                      {"channel", e.channel},
                      {"limit", limit_kind_name(e.kind)},
                      {"action", limit_action_name(e.action)},
                      {"commanded_m", e.commanded_m},
                      {"applied_m", e.applied_m},
                      {"observed", e.observed},
                      {"bound", e.bound},
                      {"cause", limit_cause_name(e.cause)}});
  }
  json hold = nullptr;
  if (report.hold_tick >= 0) {
    hold = {{"tick", report.hold_tick},
            {"periods_after_last_command", report.hold_tick - report.last_command_tick},
            {"position_m", std::vector<double>(controller.command_m().begin(), controller.command_m().end())}};
  }
  nlohmann::json summary = {
      {"node", setup.name},
      {"test_id", setup.node.test_id},
      {"site_id", setup.node.site_id},
      {"started", true},
      {"mode", setup.mode == ServoNodeSetup::Mode::kRealTime ? "real_time" : "lock_step"},
      {"control_period_s", setup.node.control_period_s},
      {"ticks", c.ticks},
      {"commands_accepted", c.accepted},
      {"commands_applied", c.applied},
      {"last_command_step", controller.newest_accepted_step()},
      {"commands_dropped", dropped},
      {"end_of_run_commands", c.dropped(CommandVerdict::kEndOfRun)},
      {"runs", c.runs},
      {"serving_run_id",
       controller.serving_run() != 0 ? json(transport::run_id_text(controller.serving_run())) : json(nullptr)},
      {"run_events", run_events},
      {"run_events_not_logged", controller.run_events_not_logged()},
      {"missed_periods", c.missed_periods},
      {"holds", c.holds},
      {"first_command_tick", report.first_command_tick},
      {"last_command_tick", report.last_command_tick},
      {"hold_after_last_command", hold},
      {"faulted", controller.faulted()},
      {"faulted_tick", report.faulted_tick},
      {"limits", limits},
      {"limit_events", events},
      {"limit_events_not_logged", controller.events_not_logged()},
      {"actuator_no_replies", c.actuator_no_replies},
      {"feedback_published", report.feedback_published},
      {"cycles", report.cycles},
      {"overruns", report.overruns},
      {"late_wakeups", report.late_wakeups},
      {"jitter", realtime::latency_json(report.jitter)},
      {"memory_locked", report.granted.memory_locked},
      {"sched_fifo", report.granted.fifo_granted},
      {"cpus_kept_awake", report.granted.cpus_kept_awake}};
  if (report.granted.pinned_cpu >= 0) summary["loop_cpu"] = report.granted.pinned_cpu;
  return summary;
}

// One line per run event: which runs the node served, and what it refused while serving them.
void log_run_events(const ServoNodeController& controller, std::ostream& log) {
  for (const auto& e : controller.run_events()) {
    log << "rpsd servo-node: tick " << e.tick << ": ";
    const std::string run = "run " + transport::run_id_text(e.run_id);
    switch (e.kind) {
      case RunEvent::Kind::kBound:
        log << "took " << run << " (first step " << e.step << ")";
        break;
      case RunEvent::Kind::kEnded:
        log << run << " ended (last step " << e.step << ")";
        break;
      case RunEvent::Kind::kReleasedAfterSilence:
        log << run << " sent nothing for a while: freed the node from it (last step " << e.step << ")";
        break;
      case RunEvent::Kind::kRefused:
        log << "refused a command of " << run << " (" << command_verdict_name(e.verdict) << ", step " << e.step
            << ", writer " << e.writer << "; serving "
            << (e.serving_run_id != 0 ? "run " + transport::run_id_text(e.serving_run_id) : std::string("no run"))
            << ")";
        break;
    }
    log << '\n';
  }
  if (controller.run_events_not_logged() > 0) {
    log << "rpsd servo-node: " << controller.run_events_not_logged() << " more run events not logged\n";
  }
}

// "5 dropped (another run 3, unknown writer 2)".
std::string dropped_text(const ServoNodeCounters& c) {
  std::string text = std::to_string(c.dropped_total()) + " dropped";
  std::string reasons;
  for (int v = 1; v < kCommandVerdicts; ++v) {
    if (v == static_cast<int>(CommandVerdict::kEndOfRun) || c.by_verdict[v] == 0) continue;
    reasons += (reasons.empty() ? "" : ", ") + std::string(command_verdict_name(static_cast<CommandVerdict>(v))) + " " +
               std::to_string(c.by_verdict[v]);
  }
  return reasons.empty() ? text : text + " (" + reasons + ")";
}

}  // namespace

nlohmann::json serve_site(const ServoNodeSetup& setup, const ServeOptions& options, const std::atomic<bool>& stop,
                          std::ostream& log) {
  const OwnedActuator actuator = make_actuator(setup.actuator, setup.node.channels);
  ServoNodeController controller(setup.node, *actuator.actuator);
  const auto* link = dynamic_cast<const ActuatorLinkReport*>(actuator.actuator.get());
  try {
    controller.start(setup.initial_displacement_m);
    // A simulated actuator is read at rest at once: a lock-step node's heartbeat tells its
    // position before the first command (the coordinator calibrates a setup from it).
    if (const auto at_rest = reading_at_rest(actuator)) controller.note_reading_at_rest(*at_rest);
  } catch (const std::runtime_error& e) {
    // The lab's controller did not answer, refused, or stands elsewhere: nothing moved, and the
    // summary says so (the link's figures name the side that failed).
    nlohmann::json summary = {{"node", setup.name}, {"test_id", setup.node.test_id}, {"site_id", setup.node.site_id},
                              {"started", false},   {"start_failure", e.what()},     {"faulted", false}};
    if (link != nullptr) summary[std::string(link->summary_key())] = link->link_summary();
    return summary;
  }

  transport::DdsParticipant participant(setup.dds);
  transport::DdsNodeEndpointConfig endpoint_config;
  endpoint_config.test_id = setup.node.test_id;
  endpoint_config.site_id = setup.node.site_id;
  endpoint_config.qos.control_period_s = setup.node.control_period_s;
  endpoint_config.qos.newest_only = setup.mode == ServoNodeSetup::Mode::kRealTime;
  transport::DdsNodeEndpoint endpoint(participant, endpoint_config);

  ServoNodeLoopOptions loop;
  loop.real_time = setup.mode == ServoNodeSetup::Mode::kRealTime;
  loop.heartbeat_rate_hz = setup.heartbeat_rate_hz;
  loop.realtime = setup.realtime;
  loop.duration_s = options.duration_s;
  log << "rpsd servo-node: test " << setup.node.test_id << " site " << setup.node.site_id << ", " << setup.node.channels
      << " channel(s), " << (loop.real_time ? "real time" : "lock-step") << " at " << 1.0 / setup.node.control_period_s
      << " Hz" << std::endl;
  if (link != nullptr) log << "rpsd servo-node: " << link->describe_link() << std::endl;
  const ServoNodeLoopReport report = run_servo_node_loop(controller, endpoint, loop, stop);
  if (!report.granted.refused.empty()) log << "rpsd servo-node: " << report.granted.refused;
  const auto& c = controller.counters();
  log_run_events(controller, log);
  log << "rpsd servo-node: stopped after " << c.ticks << " ticks, " << c.runs << " run(s), " << c.applied
      << " commands applied, " << dropped_text(c) << ", " << report.overruns << " overruns"
      << (controller.faulted() ? ", FAULTED" : "") << std::endl;
  nlohmann::json summary = node_summary(setup, controller, report);
  if (link != nullptr) summary[std::string(link->summary_key())] = link->link_summary();
  return summary;
}

nlohmann::json emulate_controller(const ControllerEmulatorSetup& setup, const ServeOptions& options,
                                  const std::atomic<bool>& stop, std::ostream& log) {
  const servo::PlantSet plants = servo::make_plants(setup.plant, setup.channels);
  ControllerEmulator emulator(plants.pointers, setup.udp);
  emulator.start(setup.initial_displacement_m);
  log << "rpsd controller-emulator: " << setup.channels << " channel(s) on udp " << setup.udp.bind_host << ":"
      << emulator.port() << ", taking datagrams from node " << emulator.node().to_string() << " only, protocol version "
      << emulator.protocol_version()
      << (emulator.protocol_version() == udp_protocol::kVersion1
              ? ": WARNING: the link is unauthenticated; whoever can send from the node's address and port commands "
                "the actuator"
              : " (HMAC-SHA-256)")
      << std::endl;
  const std::int64_t end_ns =
      options.duration_s > 0.0 ? realtime::monotonic_now_ns() + static_cast<std::int64_t>(options.duration_s * 1e9) : 0;
  while (!stop.load() && (end_ns == 0 || realtime::monotonic_now_ns() < end_ns)) emulator.serve(0.05);
  const auto& c = emulator.counters();
  log << "rpsd controller-emulator: stopped after " << c.commands_applied << " commands in " << c.sessions
      << " session(s); ignored " << c.foreign_datagrams << " foreign, " << c.unauthenticated << " unauthenticated, "
      << c.other_session << " other-session, " << c.outside_session << " outside-session, " << c.stale_commands
      << " stale and " << c.bad_packets << " bad datagrams" << std::endl;
  const auto& reading = emulator.reading();
  return {{"protocol_version", emulator.protocol_version()},
          {"node", emulator.node().to_string()},
          {"sessions", c.sessions},
          {"commands_applied", c.commands_applied},
          {"queries", c.queries},
          {"foreign_datagrams", c.foreign_datagrams},
          {"unauthenticated", c.unauthenticated},
          {"other_session", c.other_session},
          {"outside_session", c.outside_session},
          {"bad_packets", c.bad_packets},
          {"wrong_channels", c.wrong_channels},
          {"stale_commands", c.stale_commands},
          {"refused_commands", c.refused_commands},
          {"position_m",
           std::vector<double>(reading.displacement_m.begin(), reading.displacement_m.begin() + emulator.channels())}};
}

}  // namespace rpsd::node
