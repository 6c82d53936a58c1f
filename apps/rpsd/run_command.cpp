#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "progress_bar.h"
#include "rpsd/commands.h"
#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/node/servo_node_overview.h"
#include "rpsd/output/results_files.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/site_server/site_summary.h"
#include "rpsd/studies/dry_run_report.h"
#include "rpsd/studies/scenario_overview.h"
#include "rpsd/studies/study_output.h"
#include "stop_signals.h"

namespace rpsd::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out;
  std::vector<std::string> overrides;
  std::string record;
  bool dry_run = false;
  bool replace = false;
  std::vector<std::string> node_files;
  bool telemetry = false;
  std::string format;
  std::string histories;
  std::string history_rate_hz;
};

// The limits a node enforces, as `rpsd servo-node FILE` reads them.
studies::NodeLimits node_limits(const std::string& file) {
  const node::ServoNodeSetup node = scenarios::load_servo_node(file);
  studies::NodeLimits limits;
  limits.name = file;
  limits.test_id = node.node.test_id;
  limits.site_id = node.node.site_id;
  limits.control_period_s = node.node.control_period_s;
  limits.channels.assign(node.node.limits.begin(), node.node.limits.begin() + node.node.channels);
  limits.control.assign(node.node.control.begin(), node.node.control.begin() + node.node.channels);
  return limits;
}

// The pre-test check: its table on stdout, its numbers in OUT/dry-run.json; true when ready.
bool check_before_running(const hybrid_test::TestConfig& test, const std::string& out,
                          const std::vector<std::string>& node_files) {
  std::vector<studies::NodeLimits> nodes;
  for (const auto& f : node_files) nodes.push_back(node_limits(f));
  const studies::DryRunReport report = studies::dry_run(test, nodes);
  const nlohmann::json numbers = studies::report_dry_run(report, test.name, std::cout);
  if (!out.empty()) output::write_file_whole(std::filesystem::path(out) / "dry-run.json", numbers.dump(2) + '\n');
  return report.within_limits;
}

}  // namespace

std::vector<scenarios::Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<scenarios::Override> overrides;
  for (const auto& t : texts) {
    overrides.push_back(scenarios::parse_override(t));
    overrides.back().origin = "--set #" + std::to_string(overrides.size());
  }
  return overrides;
}

void add_run(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand("run", "Run a scenario and write its results (CSV, summary.json, PNG plots)");
  run->add_option("scenario", options->scenario, "Scenario file (YAML)")->required()->check(CLI::ExistingFile);
  run->add_option("--out", options->out,
                  "Output folder: created if missing, refused if it holds anything (optional with --dry-run)");
  run->add_flag("--replace", options->replace,
                "Clear the --out folder first when an earlier rpsd run or dry run wrote it");
  run->add_flag(
      "--dry-run", options->dry_run,
      "Run against the simulated plant in this process first and report predicted peaks against the limits and "
      "the stability margin; exit 4 when not ready");
  run->add_option(
         "--node", options->node_files,
         "With --dry-run: a servo node's file (rpsd servo-node); its limits are checked too (repeatable, one per site)")
      ->check(CLI::ExistingFile);
  run->add_option("--set", options->overrides, "Override a scenario key: key.path=value (repeatable)");
  // No CLI11 file check: the record reader's own (regular files only, a size cap) names
  // the problem and exits 2 like every other bad input.
  run->add_option("--record", options->record, "Drive the test with this PEER AT2 record instead of the scenario's");
  run->add_flag("--telemetry", options->telemetry,
                "Publish the test's telemetry for `rpsd monitor` (as output.telemetry: true; docs/telemetry.md)");
  run->add_option("--format", options->format,
                  "Write the histories as csv, hdf5 (results.h5, docs/results-format.md) or both (as output.format)")
      ->check(CLI::IsMember({"csv", "hdf5", "both"}));
  run->add_option("--histories", options->histories,
                  "Keep every step's histories (all), none (criteria_only: summary.json's criteria, from every step) "
                  "or every k-th step (decimated, with --history-rate-hz) (as output.histories)")
      ->check(CLI::IsMember({"all", "criteria_only", "decimated"}));
  // The rate is checked by the scenario's reader (a divisor of the control rate), as the key's.
  run->add_option("--history-rate-hz", options->history_rate_hz,
                  "With --histories decimated: the rate of the rows kept, the control rate over a whole number (as "
                  "output.history_rate_hz)");
  run->callback([options] {
    // --record replaces the record and keeps the scenario's processing; --set may then refine it.
    std::vector<scenarios::Override> overrides;
    if (!options->record.empty()) {
      overrides.push_back({"ground_motion",
                           "{file: \"" + std::filesystem::absolute(options->record).string() + "\", format: peer_at2}",
                           "--record", scenarios::Override::Kind::kRecord});
    }
    if (options->telemetry) overrides.push_back({"output.telemetry", "true", "--telemetry"});
    if (!options->format.empty()) overrides.push_back({"output.format", options->format, "--format"});
    if (!options->histories.empty()) overrides.push_back({"output.histories", options->histories, "--histories"});
    if (!options->history_rate_hz.empty()) {
      overrides.push_back({"output.history_rate_hz", options->history_rate_hz, "--history-rate-hz"});
    }
    for (auto& o : parse_overrides(options->overrides)) overrides.push_back(std::move(o));
    const auto file = scenarios::load_study(options->scenario, overrides);
    if (options->dry_run) {
      const auto* test = std::get_if<hybrid_test::TestConfig>(&file.study);
      if (!test) throw CLI::ValidationError("--dry-run", "needs an rpsd_test scenario");
      if (!options->out.empty()) output::prepare_results_folder(options->out, options->replace);
      if (!check_before_running(*test, options->out, options->node_files)) throw DryRunNotReady();
      return;
    }
    if (!options->node_files.empty()) throw CLI::ValidationError("--node", "only with --dry-run");
    if (options->out.empty()) throw CLI::ValidationError("--out", "required (except with --dry-run)");
    output::prepare_results_folder(options->out, options->replace);
    double rate_hz = 1024.0;
    const std::atomic<bool>* stop_request = nullptr;
    if (const auto* test = std::get_if<hybrid_test::TestConfig>(&file.study)) {
      rate_hz = test->control_rate_hz;
      stop_request = &stop_on_signals();  // tests and sweeps stop in order; the servo studies simply end
    }
    studies::StudyRun run;
    {
      ProgressBar bar(rate_hz);
      run = studies::run_and_write(
          file, options->out, [&bar](const hybrid_test::ProgressReport& r) { bar(r); }, stop_request);
    }
    const std::string summary = options->out + "/summary.json";
    std::cout << "rpsd run: " << file.name << " -> " << summary << "\n";
    switch (run.result) {
      case hybrid_test::RunResult::kCompleted:
        return;
      case hybrid_test::RunResult::kStopped:
        throw TestStopped(run.recorded_in, run.reason);
      case hybrid_test::RunResult::kResultsNotWritten:
        throw output::ResultsNotWritten(run.reason + "; " + summary + " says what is missing");
      case hybrid_test::RunResult::kInterrupted:
        throw RunInterrupted(summary, run.reason);
      case hybrid_test::RunResult::kNotReady:
        throw RunNotReady(summary, run.reason);
    }
  });
}

void add_validate(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  auto* validate = app.add_subcommand("validate", "Check a scenario without running it");
  validate->add_option("scenario", options->scenario, "Scenario file, a site-server file or a servo node's file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  validate->add_option("--set", options->overrides, "Override a scenario key: key.path=value (repeatable)");
  validate->callback([options] {
    if (scenarios::is_site_server_file(options->scenario)) {
      const auto site = scenarios::load_site_server(options->scenario, parse_overrides(options->overrides));
      std::cout << options->scenario << ": ok (a site-server file)\n";
      site_server::print_site_overview(site, std::cout);
      return;
    }
    if (scenarios::is_servo_node_file(options->scenario)) {
      const auto node = scenarios::load_servo_node(options->scenario, parse_overrides(options->overrides));
      std::cout << options->scenario << ": ok (a servo node's file)\n";
      node::print_node_overview(node, std::cout);
      return;
    }
    const auto file = scenarios::load_study(options->scenario, parse_overrides(options->overrides));
    std::cout << options->scenario << ": ok\n";
    if (const auto* test = std::get_if<hybrid_test::TestConfig>(&file.study)) {
      if (!file.sweep.empty()) {
        std::cout << "  sweep: " << file.sweep_cases.size() << " cases; the first:\n";
      }
      if (file.monte_carlo) {
        std::cout << "  monte_carlo: " << file.sweep_cases.size() << " runs (seed " << file.monte_carlo->seed
                  << "), each read and checked; " << file.monte_carlo->parameters.size()
                  << " keys drawn; the first run:\n";
      }
      studies::print_overview(studies::overview_of(*test), std::cout);
    }
  });
}

void add_plot(CLI::App& app) {
  auto dir = std::make_shared<std::string>();
  auto* plot = app.add_subcommand("plot", "Redraw the plots of a folder rpsd wrote (a test, a sweep, a study)");
  plot->add_option("dir", *dir, "Output folder of `rpsd run`")->required()->check(CLI::ExistingDirectory);
  plot->callback([dir] {
    const auto drawn = hybrid_test::plot_folder(*dir);
    std::cout << "rpsd plot: " << drawn.size() << " plots in " << *dir << "\n";
  });
}

}  // namespace rpsd::cli
