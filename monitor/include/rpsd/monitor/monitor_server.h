// The HTTP server of `rpsd monitor` (cpp-httplib): the page, the live stream (Server-Sent
// Events of telemetry_json.h's messages through a StreamHub), the status (stale data, lost
// link), the operator commands (POST with the token), and the viewer of recorded folders
// under results_dir (results_path.h guards every path). Reading needs no token; commanding
// does, on localhost too. Watching never writes to the test: the source is read-only.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>

#include "rpsd/monitor/command_sink.h"
#include "rpsd/monitor/stream_hub.h"
#include "rpsd/monitor/telemetry_source.h"

namespace rpsd::monitor {

struct MonitorOptions {
  std::string host = "127.0.0.1";  // another address only when asked (--listen)
  int port = 8080;                 // 0: any free port (bound_port() says which)
  std::uint32_t test_id = 1;
  std::filesystem::path results_dir;  // empty: no viewer
  std::string token;                  // operator commands need it
  double stale_after_s = 2.0;         // no batch for this long while a run goes on: stale
  double command_timeout_s = 5.0;     // for the coordinator's reply
  std::string no_commands_why;        // with no command sink: why, told to the page (none: no link)
  StreamHubOptions stream;
};

class MonitorServer {
 public:
  // source and sink may be null (no live test: the viewer only; commands refused). Both must
  // outlive the server. `log` gets every operator command (who, when, what, the reply).
  MonitorServer(MonitorOptions options, TelemetrySource* source, CommandSink* sink, std::ostream& log);
  ~MonitorServer();
  MonitorServer(const MonitorServer&) = delete;
  MonitorServer& operator=(const MonitorServer&) = delete;

  // Binds the address; throws std::invalid_argument naming it when it cannot.
  void bind();
  int bound_port() const;
  // Serves until stop() (from any thread). Reads the source on a thread of its own.
  void serve();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rpsd::monitor
