// As-fast-as-possible throughput of the seed paper's SDOF RPsD test, built exactly as
// `rpsd run scenarios/elcentro-sdof.yaml` builds it (coordinator::run_test): numerical
// mass and damping, the 700.8 kN/m specimen on the full nonlinear servo-hydraulic model
// (RK4 at its internal 8192 Hz), phase-lead compensation, central difference at 1024 Hz,
// the in-process link and the recorder hand-off to its writer thread.
//
// 60 s of record: El Centro 1940 (40 s) followed by 20 s of free vibration (the scenario's
// own `ground_motion.pad_after_s: 20`). Measured per trial: building the parts, 61,440 loop
// steps and draining the recorder; not the perfect-actuator reference run, the criteria or
// the plots that `rpsd run` adds. The writer thread writes its CSV to /dev/null (so the disk
// plays no part); a second figure writes it to a temporary file.
//
// Baseline in the same run: the plant alone (ServoHydraulicPlant::advance over the same
// 61,440 command intervals, fed the commands the test sent), so the ratio shows what the
// loop costs on top of the plant it drives.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "bench_report.h"
#include "rpsd/coordinator/test_runner.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/servo_hydraulic_plant.h"

namespace {

using namespace rpsd;

constexpr double kPadSeconds = 20.0;

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 15);
  bench::Fragment fragment("sdof_throughput", argc, argv);

  const auto file = scenarios::load_study(options.source_dir / "scenarios/elcentro-sdof.yaml",
                                          {scenarios::parse_override("ground_motion.pad_after_s=" + std::to_string(kPadSeconds))});
  const auto& scenario = std::get<scenarios::TestScenario>(file.study);
  const double simulated_s = scenario.duration_s;
  const auto& servo = std::get<servo::ServoSystemParameters>(scenario.plant);

  // One untimed run that keeps its records: checks the test completes and gives the command
  // sequence for the baseline.
  const coordinator::TestRun first = coordinator::run_test(scenario, {}, false);
  if (first.outcome != coordinator::StepOutcome::kOk && first.outcome != coordinator::StepOutcome::kRecordEnded) {
    throw std::runtime_error("the El Centro test did not complete");
  }
  if (static_cast<std::int64_t>(first.records.size()) != first.steps_planned) {
    throw std::runtime_error("the El Centro test did not record every step");
  }
  const auto steps = static_cast<double>(first.steps_planned);

  // One timed run: build the parts, step to the end, drain the recorder; as `rpsd run` runs
  // the test (no records kept in memory).
  const auto run = [&](const std::filesystem::path& csv) {
    coordinator::TestAssembly test(scenario, csv, false, false);
    coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
    for (std::int64_t n = 0; n < test.steps_planned() && outcome == coordinator::StepOutcome::kOk; ++n) outcome = test.step();
    const coordinator::TestRun done = test.finish(outcome);
    if (done.steps != first.steps_planned) throw std::runtime_error("a trial stopped early");
  };
  const auto loop_s = bench::time_trials(options.repetitions, 1, [&] { run("/dev/null"); });
  const auto loop_no_csv_s = bench::time_trials(options.repetitions, 0, [&] { run({}); });
  const std::filesystem::path tmp_csv = std::filesystem::temp_directory_path() / "rpsd-bench-time_history.csv";
  const auto loop_file_s = bench::time_trials(options.repetitions, 0, [&] { run(tmp_csv); });
  const auto csv_bytes = std::filesystem::file_size(tmp_csv);
  std::filesystem::remove(tmp_csv);

  // Baseline: the plant alone over the same command intervals.
  servo::ServoHydraulicPlant plant(servo);
  const double period_s = 1.0 / scenario.control_rate_hz;
  double sink = 0.0;
  const auto plant_s = bench::time_trials(options.repetitions, 1, [&] {
    plant.reset(0.0);
    double previous = 0.0;
    for (const auto& r : first.records) {
      plant.advance(previous, r.command_m[0], period_s);
      previous = r.command_m[0];
      sink += plant.measure().displacement_m;
    }
  });
  if (!(sink == sink)) std::puts("");  // keeps the plant's work observable

  const auto x_realtime = [&](double s) { return simulated_s / s; };
  const auto summary = [&](const std::vector<double>& seconds) { return bench::map_summary(bench::summarize(seconds), x_realtime); };
  const bench::Summary loop = summary(loop_s.wall_s);
  const bench::Summary loop_file = summary(loop_file_s.wall_s);
  const bench::Summary loop_no_csv = summary(loop_no_csv_s.wall_s);
  const bench::Summary plant_alone = summary(plant_s.wall_s);
  const int substeps = static_cast<int>(std::ceil(servo.plant_rate_hz / scenario.control_rate_hz - 1e-9));

  bench::Figure f;
  f.id = "sdof_afap_x_realtime";
  f.title = "Paper SDOF RPsD in process, as fast as possible (writer to /dev/null)";
  f.unit = "x real time";
  f.value = loop;
  f.cpu_value = summary(loop_s.cpu_s);
  f.target = ">= 1000";
  f.meets_target = loop.median >= 1000.0;
  f.baseline_id = "servo_plant_alone_x_realtime";
  f.ratio_label = "loop speed / plant-alone speed";
  f.ratio_to_baseline = loop.median / plant_alone.median;
  fragment.add(f);

  bench::Figure wall;
  wall.id = "sdof_afap_wall_ms";
  wall.title = "  the same: wall time of 60 s of record";
  wall.unit = "ms";
  wall.value = bench::map_summary(bench::summarize(loop_s.wall_s), [](double s) { return 1e3 * s; });
  wall.cpu_value = bench::map_summary(bench::summarize(loop_s.cpu_s), [](double s) { return 1e3 * s; });
  wall.target = "< 60";
  wall.meets_target = wall.value.median < 60.0;
  fragment.add(wall);

  bench::Figure per_step;
  per_step.id = "sdof_afap_step_us";
  per_step.title = "  the same: one control step (8 plant RK4 substeps)";
  per_step.unit = "us";
  per_step.value = bench::map_summary(bench::summarize(loop_s.wall_s), [&](double s) { return 1e6 * s / steps; });
  per_step.cpu_value = bench::map_summary(bench::summarize(loop_s.cpu_s), [&](double s) { return 1e6 * s / steps; });
  fragment.add(per_step);

  bench::Figure no_csv;
  no_csv.id = "sdof_afap_no_csv_x_realtime";
  no_csv.title = "  the same, no CSV (the writer thread only drains the queue)";
  no_csv.unit = "x real time";
  no_csv.value = loop_no_csv;
  no_csv.cpu_value = summary(loop_no_csv_s.cpu_s);
  no_csv.baseline_id = "sdof_afap_x_realtime";
  no_csv.ratio_label = "without CSV / with CSV to /dev/null (speed)";
  no_csv.ratio_to_baseline = loop_no_csv.median / loop.median;
  fragment.add(no_csv);

  bench::Figure file_figure;
  file_figure.id = "sdof_afap_csv_file_x_realtime";
  file_figure.title = "  the same, writer thread writing time_history.csv to a temp file";
  file_figure.unit = "x real time";
  file_figure.value = loop_file;
  file_figure.cpu_value = summary(loop_file_s.cpu_s);
  file_figure.baseline_id = "sdof_afap_x_realtime";
  file_figure.ratio_label = "to a file / to /dev/null (speed)";
  file_figure.ratio_to_baseline = loop_file.median / loop.median;
  fragment.add(file_figure);

  bench::Figure plant_figure;
  plant_figure.id = "servo_plant_alone_x_realtime";
  plant_figure.title = "Baseline: servo plant alone, RK4 at 8192 Hz, same commands";
  plant_figure.unit = "x real time";
  plant_figure.value = plant_alone;
  plant_figure.cpu_value = summary(plant_s.cpu_s);
  fragment.add(plant_figure);

  char text[400];
  std::snprintf(text, sizeof text,
                "Paper SDOF: El Centro 1940 x 0.15 (40 s) + %.0f s free vibration = %.0f s, %lld steps at %.0f Hz, "
                "plant RK4 at %.0f Hz (%d substeps per step), central difference, phase lead 90 ms / a = 20; "
                "CSV of %.1f MB per run.",
                kPadSeconds, simulated_s, static_cast<long long>(first.steps_planned), scenario.control_rate_hz,
                servo.plant_rate_hz, substeps, static_cast<double>(csv_bytes) / 1e6);
  fragment.note(text);
  fragment.note("Timed per trial: building the parts, every loop step, and draining the recorder (coordinator::TestAssembly, "
                "as `rpsd run` runs the test, no records kept in memory); not the reference run, criteria or plots of `rpsd run`. "
                "The headline figure formats every CSV row and writes it to /dev/null.");
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "sdof_throughput: %s\n", e.what());
  return 1;
}
