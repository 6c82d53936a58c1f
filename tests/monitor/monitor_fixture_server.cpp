// The monitor's server with a recorded run as its telemetry and a recording command sink,
// for the browser tests (browser/monitor_page_test.mjs): what the page plots and sends can
// then be compared with the run's time_history.csv and with the commands that arrived.
//   monitor_fixture_server REPLAY_DIR RESULTS_DIR TOKEN STEPS_PER_SECOND COMMANDS_LOG
// Prints "port N" once listening; serves until its standard input closes.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>

#include "rpsd/monitor/monitor_server.h"
#include "rpsd/monitor/recorded_telemetry_source.h"
#include "rpsd/monitor/telemetry_json.h"

namespace {

// Appends "action origin" to a file, and replies as a coordinator that acted would.
class LoggingSink final : public rpsd::monitor::CommandSink {
 public:
  explicit LoggingSink(std::string file) : file_(std::move(file)) {}
  std::optional<rpsd::operator_commands::OperatorReply> send(rpsd::operator_commands::OperatorAction action,
                                                             const std::string& origin) override {
    const std::lock_guard lock(mutex_);
    std::ofstream(file_, std::ios::app) << rpsd::monitor::action_name(action) << ' ' << origin << std::endl;
    rpsd::operator_commands::OperatorReply r;
    r.status = rpsd::operator_commands::ReplyStatus::kDone;
    std::snprintf(r.text.data(), r.text.size(), "%s received by the test's fake coordinator",
                  rpsd::monitor::action_name(action));
    return r;
  }

 private:
  std::string file_;
  std::mutex mutex_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: monitor_fixture_server REPLAY_DIR RESULTS_DIR TOKEN STEPS_PER_SECOND COMMANDS_LOG\n";
    return 2;
  }
  rpsd::monitor::RecordedRunOptions run;
  run.test_id = 31;
  run.steps_per_second = std::stod(argv[4]);
  run.predicted_effective_damping = 0.0312;
  rpsd::monitor::RecordedTelemetrySource source(argv[1], run);
  LoggingSink sink(argv[5]);
  rpsd::monitor::MonitorOptions options;
  options.port = 0;
  options.test_id = run.test_id;
  options.results_dir = argv[2];
  options.token = argv[3];
  rpsd::monitor::MonitorServer server(options, &source, &sink, std::cerr);
  server.bind();
  std::cout << "port " << server.bound_port() << std::endl;
  std::thread watcher([&] {
    std::string line;
    while (std::getline(std::cin, line)) {
    }
    server.stop();
  });
  server.serve();
  server.stop();
  watcher.join();
  return 0;
}
