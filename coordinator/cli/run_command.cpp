#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "rpsd/coordinator/study_output.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::cli {

void add_run(CLI::App& app) {
  struct Options {
    std::string scenario;
    std::string out;
  };
  auto options = std::make_shared<Options>();
  auto* run = app.add_subcommand("run", "Run a scenario and write its results (CSV, summary.json, PNG plots)");
  run->add_option("scenario", options->scenario, "Scenario file (YAML)")->required()->check(CLI::ExistingFile);
  run->add_option("--out", options->out, "Output folder (created if missing)")->required();
  run->callback([options] {
    const auto file = scenarios::load_study(options->scenario);
    coordinator::run_and_write(file, options->out);
    std::cout << "rpsd run: " << file.name << " -> " << options->out << "/summary.json\n";
  });
}

}  // namespace rpsd::cli
