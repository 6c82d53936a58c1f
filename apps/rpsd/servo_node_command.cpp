// `rpsd servo-node NODE.yaml` and `rpsd controller-emulator EMULATOR.yaml`: read the file,
// serve until SIGINT/SIGTERM (or --duration), write the summary (node/servo_node_process.h).
#include <atomic>
#include <csignal>
#include <fstream>
#include <iostream>
#include <memory>

#include "rpsd/commands.h"
#include "rpsd/node/servo_node_process.h"
#include "rpsd/scenarios/servo_node_file.h"

namespace rpsd::cli {
namespace {

// Set by the signal handler, read by the loops: the one process-wide flag a handler may touch.
std::atomic<bool> g_stop{false};
void request_stop(int) { g_stop.store(true); }

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

struct NodeOptions {
  std::string config;
  std::vector<std::string> overrides;
  std::string summary;
  double duration_s = 0.0;
};

void write_summary(const std::string& file, const nlohmann::json& summary) {
  if (!file.empty()) std::ofstream(file) << summary.dump(2) << '\n';
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
  auto* node =
      app.add_subcommand("servo-node", "Serve one site's actuators over DDS, with the node's own limits and watchdog");
  add_node_options(*node, options);
  node->callback([options] {
    const auto setup = scenarios::load_servo_node(options->config, parse_overrides(options->overrides));
    install_stop_handlers();
    write_summary(options->summary, node::serve_site(setup, {options->duration_s}, g_stop, std::cout));
  });
  auto emulator_options = std::make_shared<NodeOptions>();
  auto* emulator = app.add_subcommand("controller-emulator",
                                      "Stand in for a hardware controller on UDP (docs/udp-controller-protocol.md)");
  add_node_options(*emulator, emulator_options);
  emulator->callback([emulator_options] {
    const auto setup =
        scenarios::load_controller_emulator(emulator_options->config, parse_overrides(emulator_options->overrides));
    install_stop_handlers();
    write_summary(emulator_options->summary,
                  node::emulate_controller(setup, {emulator_options->duration_s}, g_stop, std::cout));
  });
}

}  // namespace rpsd::cli
