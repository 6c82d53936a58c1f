// Writing a test's histories as HDF5 against CSV: the paper's SDOF (El Centro, as
// `rpsd run examples/scenarios/elcentro-sdof.yaml` builds it) and its reference run as fast as
// possible, side by side as `rpsd run` runs them, once writing the two CSV tables, once
// results.h5 (docs/results-format.md), once writing nothing; trials interleaved in one run.
// Reported per simulated minute: the wall time of each, and the bytes each leaves on disk.
// As fast as possible the loop waits for the recorder's writer thread when its queue is full,
// so the time is what the writer costs; in real time the loop never waits for it.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "bench_report.h"
#include "rpsd/hdf5_output/hdf5_results.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"

namespace {

using namespace rpsd;

enum class Writer { kNone, kCsv, kHdf5 };

std::uintmax_t bytes_of(const std::filesystem::path& dir) {
  std::uintmax_t total = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) total += entry.file_size();
  return total;
}

// One run of the test and its reference into `dir` (emptied first); the bytes written.
[[gnu::noinline]] std::uintmax_t trial(const hybrid_test::TestConfig& scenario, Writer writer,
                                       const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::unique_ptr<hdf5_output::Hdf5Results> h5;
  hybrid_test::RunWatch watch;
  if (writer == Writer::kHdf5) {
    std::vector<hdf5_output::Hdf5RunLayout> runs;
    for (const char* name : {"test", "reference"}) {
      const bool reference = std::string_view(name) == "reference";
      const coordinator::RecorderOptions columns = hybrid_test::recorded_columns(scenario, reference);
      hdf5_output::Hdf5RunLayout run;
      run.name = name;
      run.control_rate_hz = scenario.control_rate_hz;
      run.channels = static_cast<int>(scenario.experimental.size());
      for (auto d : scenario.record_dofs) run.dof_numbers.push_back(static_cast<std::int64_t>(d));
      run.dof_view = columns.dof_view;
      run.held_channels = columns.held_channels;
      runs.push_back(run);
    }
    h5 = std::make_unique<hdf5_output::Hdf5Results>(dir / "results.h5", hdf5_output::Hdf5Inputs{"bench", "", {}}, runs);
    watch.observers.push_back(&h5->observer(0));
    watch.reference_observers.push_back(&h5->observer(1));
  }
  const bool csv = writer == Writer::kCsv;
  const hybrid_test::EvaluatedTest run = hybrid_test::run_test_and_reference(
      scenario, csv ? dir / "time_history.csv" : std::filesystem::path(),
      csv ? dir / "reference_history.csv" : std::filesystem::path(), {}, nullptr, watch);
  if (h5 && !h5->close().empty()) throw std::runtime_error("results.h5: " + h5->close());
  if (run.test.steps != run.test.steps_planned) throw std::runtime_error("a trial stopped early");
  return bytes_of(dir);
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 7);
  bench::Fragment fragment("results_format", argc, argv);
  const auto file = scenarios::load_study(options.source_dir / "examples/scenarios/elcentro-sdof.yaml");
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const double minutes = scenario.duration_s / 60.0;
  const auto dir = std::filesystem::temp_directory_path() / ("rpsd-bench-results-format-" + std::to_string(::getpid()));

  std::vector<double> none_s, csv_s, h5_s, ratios;
  std::uintmax_t csv_bytes = 0, h5_bytes = 0;
  (void)trial(scenario, Writer::kCsv, dir);  // warm-up: caches, page cache
  for (int r = 0; r < options.repetitions; ++r) {
    auto start = bench::Clock::now();
    (void)trial(scenario, Writer::kNone, dir);
    none_s.push_back(bench::seconds_since(start));
    start = bench::Clock::now();
    csv_bytes = trial(scenario, Writer::kCsv, dir);
    csv_s.push_back(bench::seconds_since(start));
    start = bench::Clock::now();
    h5_bytes = trial(scenario, Writer::kHdf5, dir);
    h5_s.push_back(bench::seconds_since(start));
    ratios.push_back(h5_s.back() / csv_s.back());
  }
  std::filesystem::remove_all(dir);

  const auto per_minute = [&](const std::vector<double>& seconds) {
    return bench::map_summary(bench::summarize(seconds), [&](double s) { return s / minutes; });
  };
  fragment.add(bench::figure("results_none_s_per_min",
                             "Paper SDOF and its reference, as fast as possible, writing nothing",
                             "s per simulated min", per_minute(none_s)));
  fragment.add(bench::figure("results_csv_s_per_min", "  the same writing time_history.csv and reference_history.csv",
                             "s per simulated min", per_minute(csv_s)));
  bench::Figure h5 = bench::figure("results_hdf5_s_per_min", "  the same writing results.h5 (SWMR, deflate 4)",
                                   "s per simulated min", per_minute(h5_s));
  h5.against("results_csv_s_per_min", "HDF5 / CSV (time), median of the rounds' ratios",
             bench::summarize(ratios).median);
  fragment.add(h5);
  fragment.add(bench::figure("results_csv_mb_per_min", "CSV tables (test and reference) on disk",
                             "MB per simulated min", bench::single(static_cast<double>(csv_bytes) / 1e6 / minutes)));
  fragment.add(bench::figure("results_hdf5_mb_per_min", "results.h5 (test and reference) on disk",
                             "MB per simulated min", bench::single(static_cast<double>(h5_bytes) / 1e6 / minutes)));
  char text[300];
  std::snprintf(text, sizeof text,
                "El Centro SDOF, %.1f s of record at %.0f Hz with its perfect-actuator reference, as fast as possible "
                "in process; %d rounds of nothing / CSV / HDF5, in a temporary folder.",
                scenario.duration_s, scenario.control_rate_hz, options.repetitions);
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "results_format: %s\n", e.what());
  return 1;
}
