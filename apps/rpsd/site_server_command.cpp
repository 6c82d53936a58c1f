// `rpsd site-server SITE.yaml --out DIR`: rpsd as the experimental site of an OpenSees model
// (docs/opensees.md). Listens, builds the site (its actuators at rest), waits for an allowed
// client's setup, serves that one genericClient element to its end (or to SIGINT or SIGTERM,
// seen between any two requests and in every wait), and writes time_history.csv and
// summary.json.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "rpsd/commands.h"
#include "rpsd/opensees/client_gate.h"
#include "rpsd/opensees/tcp_stream.h"
#include "rpsd/output/results_files.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/site_server/site_server.h"
#include "rpsd/site_server/site_summary.h"
#include "stop_signals.h"

namespace rpsd::cli {
namespace {

struct SiteServerOptions {
  std::string file;
  std::string out;
  bool replace = false;
  std::vector<std::string> overrides;
};

// summary.json when the server itself failed (a listener refused, a site that could not be
// built): never left saying "running".
void write_failure_summary(const std::filesystem::path& file, const site_server::SiteServerConfig& config,
                           const std::string& reason) {
  const nlohmann::json summary{{"name", config.name},
                               {"kind", "site_server"},
                               {"result", "stopped"},
                               {"outcome", "stopped"},
                               {"stopped_by", {{"kind", "server_failed"}, {"reason", reason}}},
                               {"exchanges", 0}};
  output::write_summary(file, summary.dump(2) + '\n');
}

site_server::SiteRun wait_and_serve(const site_server::SiteServerConfig& config, opensees::TcpListener& listener,
                                    site_server::SiteServer& server, const opensees::StopRequest& stop,
                                    std::string& peer) {
  opensees::GateOptions gate;
  gate.accept_timeout_s = config.accept_timeout_s;
  gate.allowed = opensees::PeerAllowList(config.allowed_clients);
  gate.session = server.session_options(stop);
  site_server::SiteRun run;
  std::optional<opensees::GenericClientSession> session = opensees::wait_for_client(
      listener, gate, run.gate,
      [](const std::string& line) { std::cout << "rpsd site-server: " << line << std::endl; });
  if (session) {
    peer = session->peer();
    std::cout << "rpsd site-server: OpenSees connected from " << peer << std::endl;
    const opensees::GateReport turned_away = run.gate;
    run = server.serve(*session);
    run.gate = turned_away;
  } else if (stop.requested()) {
    run.end = {opensees::SessionEnd::Kind::kInterrupted, "the user stopped the server before OpenSees connected"};
  } else {
    run.end = {opensees::SessionEnd::Kind::kIdle,
               "no OpenSees connected within " + std::to_string(config.accept_timeout_s) + " s"};
  }
  return run;
}

void serve(const SiteServerOptions& options) {
  // First: a signal from here on is a stop in order, never the default end of the process.
  const opensees::StopRequest stop{&stop_on_signals(), stop_signal_fd()};
  const site_server::SiteServerConfig config =
      scenarios::load_site_server(options.file, parse_overrides(options.overrides));
  const std::filesystem::path out = options.out;
  output::prepare_results_folder(out, options.replace);
  const std::filesystem::path summary_file = out / "summary.json";
  output::reserve_summary(summary_file,
                          R"json({"kind": "site_server", "result": "running", "outcome": "running (or killed)"})json");

  site_server::SiteRun run;
  std::string peer;
  std::uint16_t port = 0;
  try {
    opensees::TcpListener listener(config.listen_address, config.listen_port);
    port = listener.port();
    // The actuators are at rest, and every DDS site found, before OpenSees may connect.
    site_server::SiteServer server(config, out / "time_history.csv");
    std::cout << "rpsd site-server: " << config.name << " listening on " << config.listen_address << ":" << port
              << " for a genericClient with " << config.element_dofs
              << " basic DOF(s); clients allowed: " << site_server::allowed_clients_text(config) << std::endl;
    run = wait_and_serve(config, listener, server, stop, peer);
  } catch (const std::exception& e) {
    write_failure_summary(summary_file, config, e.what());
    throw;
  }
  if (run.peak_measured_m.empty()) {
    run.peak_measured_m.assign(config.maps.size(), 0.0);
    run.peak_force_n.assign(config.maps.size(), 0.0);
  }
  output::write_summary(summary_file, site_server::site_summary(config, run, peer, port).dump(2) + '\n');
  std::cout << "rpsd site-server: " << run.exchanges << " steps -> " << summary_file.string() << std::endl;
  switch (site_server::result_of(run)) {
    case site_server::SiteResult::kCompleted:
      return;
    case site_server::SiteResult::kStopped:
      throw TestStopped((out / "time_history.csv").string(), "stopped: " + site_server::stop_reason(run));
    case site_server::SiteResult::kInterrupted:
      throw RunInterrupted(summary_file.string(),
                           site_server::stop_reason(run) + "; nothing was commanded after it, and the actuators hold");
    case site_server::SiteResult::kResultsNotWritten:
      throw output::ResultsNotWritten(run.write_error + "; " + summary_file.string() + " says what is missing");
  }
}

}  // namespace

void add_site_server(CLI::App& app) {
  auto options = std::make_shared<SiteServerOptions>();
  auto* command = app.add_subcommand(
      "site-server",
      "Serve an OpenSees genericClient element as the experimental site of its model (docs/opensees.md)");
  command->add_option("site", options->file, "Site file (YAML)")->required()->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "Output folder: created if missing, refused if it holds anything")
      ->required();
  command->add_flag("--replace", options->replace, "Clear the --out folder first when an earlier rpsd run wrote it");
  command->add_option("--set", options->overrides, "Override a key of the site file: key.path=value (repeatable)");
  command->callback([options] { serve(*options); });
}

}  // namespace rpsd::cli
