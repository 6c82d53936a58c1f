#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "progress_bar.h"
#include "rpsd/commands.h"
#include "rpsd/commands/dry_run_check.h"
#include "rpsd/commands/run_scenario.h"
#include "rpsd/commands/validate_report.h"
#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/output/results_files.h"
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
  bool json = false;
  std::string histories;
  std::string history_rate_hz;
};

}  // namespace

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
  run->add_flag("--json", options->json,
                "With --dry-run: print the report as JSON (as dry-run.json) instead of a table");
  run->callback([options] {
    const auto file = commands::load_run_scenario(
        options->scenario, commands::run_overrides({options->record, options->telemetry, options->format,
                                                    options->histories, options->history_rate_hz},
                                                   parse_overrides(options->overrides)));
    if (options->dry_run) {
      if (!options->out.empty()) output::prepare_results_folder(options->out, options->replace);
      std::ostringstream table;
      const commands::DryRunCheck check = commands::dry_run_check(file, options->node_files, table);
      std::cout << (options->json ? check.report.dump(2) + '\n' : table.str());
      if (!options->out.empty()) {
        output::write_file_whole(std::filesystem::path(options->out) / "dry-run.json", check.report.dump(2) + '\n');
      }
      if (!check.ready) throw DryRunNotReady();
      return;
    }
    if (options->json) throw CLI::ValidationError("--json", "only with --dry-run");
    if (!options->node_files.empty()) throw CLI::ValidationError("--node", "only with --dry-run");
    if (options->out.empty()) throw CLI::ValidationError("--out", "required (except with --dry-run)");
    commands::ScenarioRunOptions run_options;
    run_options.out = options->out;
    run_options.replace = options->replace;
    double rate_hz = 1024.0;
    if (const auto* test = std::get_if<hybrid_test::TestConfig>(&file.study)) {
      rate_hz = test->control_rate_hz;
      run_options.stop_request = &stop_on_signals();
    }
    studies::StudyRun run;
    {
      ProgressBar bar(rate_hz);
      run_options.progress = [&bar](const hybrid_test::ProgressReport& r) { bar(r); };
      run = commands::run_scenario(file, run_options);
    }
    const std::string summary = options->out + "/summary.json";
    std::cout << "rpsd run: " << file.name << " -> " << summary << "\n";
    commands::throw_unless_completed(run, summary);
  });
}

void add_validate(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  auto* validate = app.add_subcommand("validate", "Check a scenario without running it");
  validate->add_option("scenario", options->scenario, "Scenario file, a site-server file or a servo node's file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  validate->add_option("--set", options->overrides, "Override a scenario key: key.path=value (repeatable)");
  validate->add_flag("--json", options->json, "Print what was understood as JSON instead of text");
  validate->callback([options] {
    std::ostringstream text;
    const nlohmann::json report = commands::validate_file(options->scenario, parse_overrides(options->overrides), text);
    std::cout << (options->json ? report.dump(2) + '\n' : text.str());
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
