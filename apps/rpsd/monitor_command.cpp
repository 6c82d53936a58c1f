// `rpsd monitor --test-id N`: the test's live page and the viewer of recorded folders, served
// on localhost unless --listen names another address. Reads the test's telemetry as a
// participant that never commands; sends the page's operator commands, which need the token
// printed here. Serves until SIGINT or SIGTERM.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "rpsd/commands.h"
#include "rpsd/monitor/access_token.h"
#include "rpsd/monitor/dds_command_sink.h"
#include "rpsd/monitor/dds_telemetry_source.h"
#include "rpsd/monitor/monitor_server.h"
#include "rpsd/operator_commands/operator_command_sender.h"
#include "stop_signals.h"

namespace rpsd::cli {
namespace {

struct MonitorOptions {
  std::uint32_t test_id = 1;
  std::uint32_t domain_id = 0;
  std::string dds_config;
  std::string listen = "127.0.0.1:8080";
  std::string results;
  double reply_timeout_s = 5.0;
};

// "HOST:PORT" (an IPv4 address or a name; port 0: any free one).
void parse_listen(const std::string& text, monitor::MonitorOptions& options) {
  const std::size_t colon = text.rfind(':');
  const auto bad = [&] {
    return std::invalid_argument("--listen " + text + ": expected HOST:PORT, e.g. 127.0.0.1:8080 or 0.0.0.0:8080");
  };
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) throw bad();
  options.host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  if (port.find_first_not_of("0123456789") != std::string::npos || port.size() > 5) throw bad();
  options.port = std::stoi(port);
  if (options.port > 65535) throw bad();
}

bool loopback(const std::string& host) { return host == "localhost" || host.rfind("127.", 0) == 0 || host == "::1"; }

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown-host";
  return name;
}

void run_monitor(const MonitorOptions& args) {
  monitor::MonitorOptions options;
  parse_listen(args.listen, options);
  options.test_id = args.test_id;
  options.command_timeout_s = args.reply_timeout_s;
  if (!args.results.empty()) {
    if (!std::filesystem::is_directory(args.results)) {
      throw std::invalid_argument("--results " + args.results + ": not a folder");
    }
    options.results_dir = args.results;
  }
  options.token = monitor::draw_access_token();

  telemetry::TelemetrySubscriberConfig telemetry_config;
  telemetry_config.domain_id = args.domain_id;
  telemetry_config.dds_config = args.dds_config;
  telemetry_config.test_id = args.test_id;
  monitor::DdsTelemetrySource source(telemetry_config);
  operator_commands::OperatorLinkConfig link;
  link.domain_id = args.domain_id;
  link.dds_config = args.dds_config;
  link.test_id = args.test_id;
  // Under DDS Security a monitor's identity (read-only) may not send operator commands: the
  // monitor still shows the test, and the page's buttons are refused with the reason.
  std::unique_ptr<monitor::DdsCommandSink> sink;
  try {
    sink = std::make_unique<monitor::DdsCommandSink>(link, "monitor@" + host_name(), args.reply_timeout_s);
  } catch (const operator_commands::OperatorNotPermitted& e) {
    options.no_commands_why = std::string("refused: ") + e.what();
  }

  const std::atomic<bool>& stop_requested = stop_on_signals();
  monitor::MonitorServer server(options, &source, sink.get(), std::cout);
  server.bind();
  const std::string address = "http://" +
                              (options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host) +
                              ":" + std::to_string(server.bound_port()) + "/";
  std::cout << "rpsd monitor: test " << args.test_id << " on DDS domain " << args.domain_id << "\n"
            << "  page:     " << address << "\n"
            << "  operator: " << address << "#token=" << options.token
            << "  (the page with the token: operators only)\n"
            << "  token:    " << options.token << "\n";
  if (!loopback(options.host)) {
    std::cout << "  warning: listening on " << options.host
              << ": anyone who reaches this address can watch the test; commands still need the token\n";
  }
  if (!sink) std::cout << "  operator commands: none from this monitor (" << options.no_commands_why << ")\n";
  if (!options.results_dir.empty()) std::cout << "  viewer:   the folders under " << args.results << "\n";
  std::cout << "  the rig's hardware emergency stop stays the primary stop; SIGINT or SIGTERM ends the monitor"
            << std::endl;

  std::atomic<bool> served{false};
  std::thread watcher([&] {
    while (!served.load()) {
      if (stop_requested.load()) server.stop();  // again until serve() returns: it may not listen yet
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  server.serve();
  served.store(true);
  watcher.join();
  server.stop();
  std::cout << "rpsd monitor: stopped" << std::endl;
}

}  // namespace

void add_monitor(CLI::App& app) {
  auto args = std::make_shared<MonitorOptions>();
  auto* cmd = app.add_subcommand("monitor",
                                 "Watch a running test in a browser (live plots, limit events, stop/abort/hold/resume "
                                 "with a token) and view recorded output folders");
  cmd->add_option("--test-id", args->test_id, "the test to watch (its DDS partition)")->required();
  cmd->add_option("--domain", args->domain_id, "the DDS domain of the test")->capture_default_str();
  cmd->add_option("--dds-config", args->dds_config,
                  "Cyclone DDS XML (with DDS Security: the monitor's identity); default CYCLONEDDS_URI")
      ->check(CLI::ExistingFile);
  cmd->add_option("--listen", args->listen,
                  "HOST:PORT to serve the page on; another address than localhost only when asked")
      ->capture_default_str();
  cmd->add_option("--results", args->results, "a folder of rpsd output folders the page's viewer may open");
  cmd->add_option("--reply-timeout", args->reply_timeout_s, "seconds to wait for the coordinator's reply to a command")
      ->check(CLI::Range(0.1, 60.0))
      ->capture_default_str();
  cmd->callback([args] { run_monitor(*args); });
}

}  // namespace rpsd::cli
