// `rpsd site-server SITE.yaml --out DIR`: rpsd as the experimental site of an OpenSees model
// (docs/opensees.md). Listens, builds the site (its actuators at rest), serves one
// genericClient element to its end, and writes time_history.csv and summary.json.
#include <filesystem>
#include <iostream>
#include <memory>

#include "rpsd/commands.h"
#include "rpsd/opensees/tcp_stream.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/site_server/site_server.h"
#include "rpsd/site_server/site_summary.h"
#include "rpsd/studies/results_files.h"
#include "stop_signals.h"

namespace rpsd::cli {
namespace {

struct SiteServerOptions {
  std::string file;
  std::string out;
  bool replace = false;
  std::vector<std::string> overrides;
};

void serve(const SiteServerOptions& options) {
  const site_server::SiteServerConfig config =
      scenarios::load_site_server(options.file, parse_overrides(options.overrides));
  const std::filesystem::path out = options.out;
  studies::prepare_results_folder(out, options.replace);
  const std::filesystem::path summary_file = out / "summary.json";
  studies::reserve_summary(summary_file, R"({"kind": "site_server", "outcome": "running"})");
  const std::atomic<bool>& stop = stop_on_signals();

  opensees::TcpListener listener(config.listen_address, config.listen_port);
  // The actuators are at rest, and every DDS site found, before OpenSees may connect.
  site_server::SiteServer server(config, out / "time_history.csv");
  std::cout << "rpsd site-server: " << config.name << " listening on " << config.listen_address << ":"
            << listener.port() << " for a genericClient with " << config.element_dofs << " basic DOF(s)" << std::endl;

  std::optional<opensees::TcpStream> client;
  for (double waited = 0.0; !client && waited < config.accept_timeout_s && !stop.load(); waited += 0.2) {
    client = listener.accept(0.2);
  }
  site_server::SiteRun run;
  std::string peer;
  if (client) {
    peer = client->peer();
    std::cout << "rpsd site-server: OpenSees connected from " << peer << std::endl;
    run = server.serve(std::move(*client), &stop);
  } else if (stop.load()) {
    run.end = {opensees::SessionEnd::Kind::kInterrupted, "the user stopped the server before OpenSees connected"};
  } else {
    run.end = {opensees::SessionEnd::Kind::kIdle,
               "no OpenSees connected within " + std::to_string(config.accept_timeout_s) + " s"};
  }
  if (run.peak_measured_m.empty()) {
    run.peak_measured_m.assign(config.maps.size(), 0.0);
    run.peak_force_n.assign(config.maps.size(), 0.0);
  }
  studies::write_summary(summary_file, site_server::site_summary(config, run, peer, listener.port()).dump(2) + '\n');
  std::cout << "rpsd site-server: " << run.exchanges << " steps -> " << summary_file.string() << std::endl;
  switch (site_server::result_of(run)) {
    case site_server::SiteResult::kCompleted:
      return;
    case site_server::SiteResult::kStopped:
      throw TestStopped((out / "time_history.csv").string(), "stopped: " + site_server::stop_reason(run));
    case site_server::SiteResult::kInterrupted:
      throw RunInterrupted(summary_file.string(), site_server::stop_reason(run));
    case site_server::SiteResult::kResultsNotWritten:
      throw studies::ResultsNotWritten(run.write_error + "; " + summary_file.string() + " says what is missing");
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
