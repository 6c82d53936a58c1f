// `rpsd servo-node NODE.yaml` and `rpsd controller-emulator EMULATOR.yaml`: read the file,
// serve until SIGINT/SIGTERM (or --duration), write the summary (node/servo_node_process.h).
#include <atomic>
#include <csignal>
#include <iostream>

#include "rpsd/commands.h"
#include "rpsd/node/servo_node_process.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "serving_command.h"

namespace rpsd::cli {
namespace {

// Set by the signal handler, read by the loops: the one process-wide flag a handler may touch.
std::atomic<bool> g_stop{false};
void request_node_stop(int) { g_stop.store(true); }

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = request_node_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace

void add_servo_node(CLI::App& app) {
  add_serving_command(
      app, "servo-node", "Serve one site's actuators over DDS, with the node's own limits and watchdog",
      "Configuration file (YAML)",
      [](const auto& file, const auto& overrides, const auto& options) {
        const auto setup = scenarios::load_servo_node(file, overrides);
        install_stop_handlers();
        return node::serve_site(setup, options, g_stop, std::cout);
      },
      [](const nlohmann::json& summary) {
        // Not ready (exit 4): the summary, written first, says which side failed.
        if (!summary.value("started", true)) throw NodeNotReady(summary.value("start_failure", std::string()));
      });
  add_serving_command(app, "controller-emulator",
                      "Stand in for a hardware controller on UDP (docs/udp-controller-protocol.md)",
                      "Configuration file (YAML)", [](const auto& file, const auto& overrides, const auto& options) {
                        const auto setup = scenarios::load_controller_emulator(file, overrides);
                        install_stop_handlers();
                        return node::emulate_controller(setup, options, g_stop, std::cout);
                      });
}

}  // namespace rpsd::cli
