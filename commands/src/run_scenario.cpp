#include "rpsd/commands/run_scenario.h"

#include <stdexcept>

#include "rpsd/output/results_files.h"

namespace rpsd::commands {

studies::StudyDocument load_run_scenario(const std::filesystem::path& scenario,
                                         const std::vector<scenarios::Override>& overrides,
                                         const hybrid_test::ExternalParts& external) {
  studies::StudyDocument file = scenarios::load_study(scenario, overrides, external);
  // One results.h5 per test: a sweep's or a batch's cases are written as CSV (docs/results-format.md).
  if (const auto* test = std::get_if<hybrid_test::TestConfig>(&file.study);
      test && test->results_format != hybrid_test::ResultsFormat::kCsv && (!file.sweep.empty() || file.monte_carlo)) {
    throw std::invalid_argument("--format: " + scenario.string() +
                                ": output.format hdf5 or both is for a single test; " +
                                "a sweep or a Monte Carlo batch writes CSV (docs/results-format.md)");
  }
  return file;
}

bool is_single_test(const studies::StudyDocument& file) {
  return std::holds_alternative<hybrid_test::TestConfig>(file.study) && file.sweep.empty() && !file.monte_carlo;
}

studies::StudyRun run_scenario(const studies::StudyDocument& file, const ScenarioRunOptions& options) {
  if (options.prepare) output::prepare_results_folder(options.out, options.replace);
  // Tests, sweeps and batches stop in order; the servo studies simply end.
  const std::atomic<bool>* stop_request =
      std::holds_alternative<hybrid_test::TestConfig>(file.study) ? options.stop_request : nullptr;
  return studies::run_and_write(file, options.out, options.progress, stop_request);
}

}  // namespace rpsd::commands
