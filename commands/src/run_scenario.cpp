#include "rpsd/commands/run_scenario.h"

#include "rpsd/output/results_files.h"

namespace rpsd::commands {

studies::StudyDocument load_run_scenario(const std::filesystem::path& scenario,
                                         const std::vector<scenarios::Override>& overrides,
                                         const hybrid_test::ExternalParts& external) {
  return scenarios::load_study(scenario, overrides, external);
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
