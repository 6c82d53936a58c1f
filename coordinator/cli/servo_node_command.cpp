// `rpsd servo-node NODE.yaml`: one site's actuators behind DDS, with the node's own limits
// and watchdog; and `rpsd controller-emulator EMULATOR.yaml`, a stand-in for the hardware
// controller that the node's UDP adapter talks to. Both stop on SIGINT/SIGTERM and write
// what they did (counters, limit events, timing) to --summary.
#include <atomic>
#include <csignal>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "rpsd/coordinator/latency_json.h"
#include "rpsd/coordinator/plant_factory.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/servo/controller_emulator.h"
#include "rpsd/servo/servo_node_loop.h"
#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::cli {
namespace {

// Set by the signal handler, read by the loops: the one process-wide flag a handler may touch.
std::atomic<bool> g_stop{false};
void request_stop(int) { g_stop.store(true); }

void install_stop_handlers() {
  struct sigaction action{};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

nlohmann::json node_summary(const scenarios::ServoNodeFile& file, const servo::ServoNodeController& controller,
                            const servo::ServoNodeLoopReport& report) {
  using nlohmann::json;
  const auto& c = controller.counters();
  json dropped = json::object();
  for (int v = 1; v < servo::kCommandVerdicts; ++v) {
    dropped[servo::command_verdict_name(static_cast<servo::CommandVerdict>(v))] = c.by_verdict[v];
  }
  json limits = json::object();
  for (int k = 0; k < servo::kLimitKinds; ++k) {
    limits[servo::limit_kind_name(static_cast<servo::LimitKind>(k))] = {{"activations", c.limit_activations[k]},
                                                                        {"active_ticks", c.limit_active_ticks[k]}};
  }
  json events = json::array();
  for (const auto& e : controller.events()) {
    events.push_back({{"tick", e.tick}, {"step", e.step}, {"channel", e.channel},
                      {"limit", servo::limit_kind_name(e.kind)}, {"action", servo::limit_action_name(e.action)},
                      {"commanded_m", e.commanded_m}, {"applied_m", e.applied_m}, {"observed", e.observed}, {"bound", e.bound}});
  }
  json hold = nullptr;
  if (report.hold_tick >= 0) {
    hold = {{"tick", report.hold_tick},
            {"periods_after_last_command", report.hold_tick - report.last_command_tick},
            {"position_m", std::vector<double>(controller.command_m().begin(), controller.command_m().end())}};
  }
  return {{"node", file.name},
          {"test_id", file.node.test_id},
          {"site_id", file.node.site_id},
          {"mode", file.mode == scenarios::ServoNodeFile::Mode::kRealTime ? "real_time" : "lock_step"},
          {"control_period_s", file.node.control_period_s},
          {"ticks", c.ticks},
          {"commands_accepted", c.accepted},
          {"commands_applied", c.applied},
          {"last_command_step", controller.newest_accepted_step()},
          {"commands_dropped", dropped},
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
          {"jitter", coordinator::latency_json(report.jitter)},
          {"memory_locked", report.granted.memory_locked},
          {"sched_fifo", report.granted.fifo_granted},
          {"cpus_kept_awake", report.granted.cpus_kept_awake}};
}

struct NodeOptions {
  std::string config;
  std::vector<std::string> overrides;
  std::string summary;
  double duration_s = 0.0;
};

void run_servo_node(const NodeOptions& o) {
  const auto file = scenarios::load_servo_node(o.config, parse_overrides(o.overrides));
  // The actuator: simulated plants (owned here) or the UDP controller adapter.
  coordinator::PlantSet plants;
  std::unique_ptr<servo::Actuator> actuator;
  if (const auto* sim = std::get_if<scenarios::SimulatedActuatorSection>(&file.actuator)) {
    plants = coordinator::make_plants(sim->plant, file.node.channels);
    actuator = std::make_unique<servo::SimulatedActuator>(plants.pointers);
  } else {
    actuator = std::make_unique<servo::UdpControllerActuator>(std::get<servo::UdpControllerConfig>(file.actuator));
  }
  servo::ServoNodeController controller(file.node, *actuator);
  controller.start(file.initial_displacement_m);

  transport::DdsParticipant participant(file.dds);
  transport::DdsNodeEndpointConfig endpoint_config;
  endpoint_config.test_id = file.node.test_id;
  endpoint_config.site_id = file.node.site_id;
  endpoint_config.qos.control_period_s = file.node.control_period_s;
  endpoint_config.qos.newest_only = file.mode == scenarios::ServoNodeFile::Mode::kRealTime;
  transport::DdsNodeEndpoint endpoint(participant, endpoint_config);

  servo::ServoNodeLoopOptions options;
  options.real_time = file.mode == scenarios::ServoNodeFile::Mode::kRealTime;
  options.heartbeat_rate_hz = file.heartbeat_rate_hz;
  options.realtime = file.realtime;
  options.duration_s = o.duration_s;
  install_stop_handlers();
  std::cout << "rpsd servo-node: test " << file.node.test_id << " site " << file.node.site_id << ", "
            << file.node.channels << " channel(s), " << (options.real_time ? "real time" : "lock-step") << " at "
            << 1.0 / file.node.control_period_s << " Hz" << std::endl;
  const servo::ServoNodeLoopReport report = run_servo_node_loop(controller, endpoint, options, g_stop);
  if (!report.granted.refused.empty()) std::cerr << "rpsd servo-node: " << report.granted.refused;
  const auto summary = node_summary(file, controller, report);
  if (!o.summary.empty()) std::ofstream(o.summary) << summary.dump(2) << '\n';
  std::cout << "rpsd servo-node: stopped after " << controller.counters().ticks << " ticks, "
            << controller.counters().applied << " commands applied, " << controller.counters().dropped_total()
            << " dropped, " << report.overruns << " overruns" << (controller.faulted() ? ", FAULTED" : "") << std::endl;
}

void run_controller_emulator(const NodeOptions& o) {
  const auto file = scenarios::load_controller_emulator(o.config, parse_overrides(o.overrides));
  const coordinator::PlantSet plants = coordinator::make_plants(file.plant, file.channels);
  servo::ControllerEmulatorConfig config;
  config.bind_host = file.bind_host;
  config.port = file.port;
  servo::ControllerEmulator emulator(plants.pointers, config);
  emulator.start(file.initial_displacement_m);
  install_stop_handlers();
  std::cout << "rpsd controller-emulator: " << file.channels << " channel(s) on udp " << file.bind_host << ":"
            << emulator.port() << std::endl;
  const std::int64_t end_ns = o.duration_s > 0.0 ? realtime::monotonic_now_ns() + static_cast<std::int64_t>(o.duration_s * 1e9) : 0;
  while (!g_stop.load() && (end_ns == 0 || realtime::monotonic_now_ns() < end_ns)) emulator.serve(0.05);
  const auto& c = emulator.counters();
  const nlohmann::json summary = {{"commands_applied", c.commands_applied}, {"queries", c.queries},
                                  {"bad_packets", c.bad_packets}, {"wrong_channels", c.wrong_channels},
                                  {"stale_commands", c.stale_commands}, {"refused_commands", c.refused_commands}};
  if (!o.summary.empty()) std::ofstream(o.summary) << summary.dump(2) << '\n';
  std::cout << "rpsd controller-emulator: stopped after " << c.commands_applied << " commands, " << c.bad_packets
            << " bad packets ignored" << std::endl;
}

void add_node_options(CLI::App& command, const std::shared_ptr<NodeOptions>& o) {
  command.add_option("config", o->config, "Configuration file (YAML)")->required()->check(CLI::ExistingFile);
  command.add_option("--set", o->overrides, "Override a key: key.path=value (repeatable)");
  command.add_option("--summary", o->summary, "Write what the process did (JSON) here when it stops");
  command.add_option("--duration", o->duration_s, "Stop after this many seconds (default: on SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace

void add_servo_node(CLI::App& app) {
  auto options = std::make_shared<NodeOptions>();
  auto* node = app.add_subcommand("servo-node", "Serve one site's actuators over DDS, with the node's own limits and watchdog");
  add_node_options(*node, options);
  node->callback([options] { run_servo_node(*options); });
  auto emulator_options = std::make_shared<NodeOptions>();
  auto* emulator = app.add_subcommand("controller-emulator",
                                      "Stand in for a hardware controller on UDP (docs/udp-controller-protocol.md)");
  add_node_options(*emulator, emulator_options);
  emulator->callback([emulator_options] { run_controller_emulator(*emulator_options); });
}

}  // namespace rpsd::cli
