// As-fast-as-possible throughput of the seed paper's SDOF RPsD test, built exactly as
// `rpsd run examples/scenarios/elcentro-sdof.yaml` builds it (hybrid_test::TestAssembly): numerical
// mass and damping, the 700.8 kN/m specimen on the full nonlinear servo-hydraulic model
// (RK4 at its internal 8192 Hz), phase-lead compensation, central difference at 1024 Hz,
// the in-process link and the recorder hand-off to its writer thread.
//
// 60 s of record: El Centro 1940 (40 s) followed by 20 s of free vibration (the scenario's
// own `ground_motion.pad_after_s: 20`; 59.99 s, 61,429 steps). Measured per trial: building the parts, the loop
// steps and draining the recorder; not the perfect-actuator reference run, the criteria or
// the plots that `rpsd run` adds. Headline: the writer thread drains the queue and writes no
// CSV (no disk, no formatting: the loop and its hand-off); further figures with the CSV
// formatted to /dev/null and written to a temporary file.
//
// Baseline in the same run: the plant alone (ServoHydraulicPlant::advance over the same
// 61,429 command intervals, fed the commands the test sent), so the ratio shows what the
// loop costs on top of the plant it drives. Loop and plant trials alternate, and the ratio
// reported is the median of the pairs' ratios, with their spread.
//
// The instructions behind the ratio, which do not depend on the load: bench/sdof-instructions
// (callgrind on loop_trial and plant_trial).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <vector>

#include "bench_report.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "unique_temp_file.h"

namespace {

using namespace rpsd;

constexpr double kPadSeconds = 20.0;

// One trial of the loop: build the parts, step to the end, drain the recorder; as `rpsd run`
// runs the test (no records kept in memory). Not inlined: a profiler can count it alone.
[[gnu::noinline]] void loop_trial(const hybrid_test::TestConfig& scenario, const std::filesystem::path& csv,
                                  std::int64_t steps) {
  hybrid_test::TestAssembly test(scenario, {csv, false, false, {}});
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
  for (std::int64_t n = 0; n < test.steps_planned() && outcome == coordinator::StepOutcome::kOk; ++n)
    outcome = test.step();
  const hybrid_test::TestRun done = test.finish(outcome);
  if (done.steps != steps) throw std::runtime_error("a trial stopped early");
}

// One trial of the baseline: the plant alone over the same command intervals. Returns a sum
// of its measurements, which keeps its work observable. Not inlined, as loop_trial.
[[gnu::noinline]] double plant_trial(servo::ServoHydraulicPlant& plant, const std::vector<double>& commands_m,
                                     double period_s) {
  plant.reset(0.0);
  double previous = 0.0, sum = 0.0;
  for (const double command : commands_m) {
    plant.advance(previous, command, period_s);
    previous = command;
    sum += plant.measure().displacement_m;
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 15);
  bench::Fragment fragment("sdof_throughput", argc, argv);

  const auto file =
      scenarios::load_study(options.source_dir / "examples/scenarios/elcentro-sdof.yaml",
                            {scenarios::parse_override("ground_motion.pad_after_s=" + std::to_string(kPadSeconds))});
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const double simulated_s = scenario.duration_s;
  const auto& servo = std::get<servo::ServoSystemParameters>(scenario.plant);

  // One untimed run that keeps its records: checks the test completes and gives the command
  // sequence for the baseline.
  const hybrid_test::TestRun first = hybrid_test::run_test(scenario, {}, false);
  if (first.outcome != coordinator::StepOutcome::kOk && first.outcome != coordinator::StepOutcome::kRecordEnded) {
    throw std::runtime_error("the El Centro test did not complete");
  }
  if (static_cast<std::int64_t>(first.records.size()) != first.steps_planned) {
    throw std::runtime_error("the El Centro test did not record every step");
  }
  const auto steps = static_cast<double>(first.steps_planned);

  // The baseline's plant and the commands the test sent.
  servo::ServoHydraulicPlant plant(servo);
  std::vector<double> commands_m;
  commands_m.reserve(first.records.size());
  for (const auto& r : first.records) commands_m.push_back(r.command_m[0]);
  const double period_s = 1.0 / scenario.control_rate_hz;
  double sink = 0.0;

  // Loop, plant, loop, plant, ... after one untimed trial of each: both trials of a pair see
  // the same machine, so a pair's ratio is what other jobs on a shared machine disturb least.
  const auto run_loop = [&] { loop_trial(scenario, {}, first.steps_planned); };
  const auto run_plant = [&] { sink += plant_trial(plant, commands_m, period_s); };
  run_loop();
  run_plant();
  bench::Trials loop_no_csv_s, plant_s;
  std::vector<double> pair_ratios, cpu_pair_ratios;  // loop speed / plant speed = plant time / loop time
  const auto time_one = [](bench::Trials& trials, const std::function<void()>& body) {
    const bench::Trials one = bench::time_trials(1, 0, body);
    trials.wall_s.push_back(one.wall_s[0]);
    trials.cpu_s.push_back(one.cpu_s[0]);
  };
  for (int i = 0; i < options.repetitions; ++i) {
    time_one(loop_no_csv_s, run_loop);
    time_one(plant_s, run_plant);
    pair_ratios.push_back(plant_s.wall_s.back() / loop_no_csv_s.wall_s.back());
    cpu_pair_ratios.push_back(plant_s.cpu_s.back() / loop_no_csv_s.cpu_s.back());
  }
  if (!(sink == sink)) std::puts("");

  const auto loop_s =
      bench::time_trials(options.repetitions, 0, [&] { loop_trial(scenario, "/dev/null", first.steps_planned); });
  // A file of this run's own (two runs at once once wrote one fixed name), removed at the end.
  const bench::UniqueTempFile tmp_csv("rpsd-bench-time_history-", ".csv");
  const auto loop_file_s =
      bench::time_trials(options.repetitions, 0, [&] { loop_trial(scenario, tmp_csv.path(), first.steps_planned); });
  const auto csv_bytes = std::filesystem::file_size(tmp_csv.path());

  const auto x_realtime = [&](double s) { return simulated_s / s; };
  const auto summary = [&](const std::vector<double>& seconds) {
    return bench::map_summary(bench::summarize(seconds), x_realtime);
  };
  const bench::Summary loop_no_csv = summary(loop_no_csv_s.wall_s);
  const bench::Summary plant_alone = summary(plant_s.wall_s);
  const bench::Summary ratio = bench::summarize(pair_ratios);
  const bench::Summary cpu_ratio = bench::summarize(cpu_pair_ratios);
  const int substeps = static_cast<int>(std::ceil(servo.plant_rate_hz / scenario.control_rate_hz - 1e-9));

  // Headline: the loop and its recorder hand-off, the writer thread draining the queue
  // without writing (no disk, no text formatting); then the same with the CSV formatted.
  const auto loop_figure = [&](bench::Figure f, const bench::Trials& t, const std::string& baseline_id,
                               const std::string& ratio_label, double ratio_to_baseline) {
    f.unit = "x real time";
    f.value = summary(t.wall_s);
    f.cpu_value = summary(t.cpu_s);
    f.against(baseline_id, ratio_label, ratio_to_baseline);
    fragment.add(f);
  };
  bench::Figure headline;
  headline.id = "sdof_afap_x_realtime";
  headline.title = "Paper SDOF RPsD in process, as fast as possible (loop + recorder hand-off)";
  headline.aiming_for(">= 1000", loop_no_csv.median >= 1000.0);
  loop_figure(headline, loop_no_csv_s, "servo_plant_alone_x_realtime",
              "loop speed / plant-alone speed, median of the interleaved pairs' ratios", ratio.median);

  // The ratio itself, pair by pair: its spread says how far one run's figure can be trusted.
  bench::Figure pairs = bench::figure("sdof_afap_vs_plant_ratio",
                                      "  the same against the plant alone: ratio of speeds in each interleaved pair",
                                      "loop / plant", ratio, cpu_ratio);
  pairs.aiming_for(">= 0.9", ratio.median >= 0.9);
  fragment.add(pairs);

  bench::Figure wall;
  wall.id = "sdof_afap_wall_ms";
  wall.title = "  the same: wall time of 60 s of record";
  wall.unit = "ms";
  wall.value = bench::map_summary(bench::summarize(loop_no_csv_s.wall_s), [](double s) { return 1e3 * s; });
  wall.cpu_value = bench::map_summary(bench::summarize(loop_no_csv_s.cpu_s), [](double s) { return 1e3 * s; });
  wall.target = "< 60";
  wall.meets_target = wall.value.median < 60.0;
  fragment.add(wall);

  fragment.add(bench::figure(
      "sdof_afap_step_us", "  the same: one control step (8 plant RK4 substeps)", "us",
      bench::map_summary(bench::summarize(loop_no_csv_s.wall_s), [&](double s) { return 1e6 * s / steps; }),
      bench::map_summary(bench::summarize(loop_no_csv_s.cpu_s), [&](double s) { return 1e6 * s / steps; })));

  bench::Figure devnull;
  devnull.id = "sdof_afap_csv_devnull_x_realtime";
  devnull.title = "  the same, writer thread formatting time_history.csv to /dev/null";
  loop_figure(devnull, loop_s, "sdof_afap_x_realtime", "with CSV / without (speed)",
              summary(loop_s.wall_s).median / loop_no_csv.median);

  bench::Figure file_figure;
  file_figure.id = "sdof_afap_csv_file_x_realtime";
  file_figure.title = "  the same, writer thread writing time_history.csv to a temp file";
  loop_figure(file_figure, loop_file_s, "sdof_afap_x_realtime", "with CSV file / without (speed)",
              summary(loop_file_s.wall_s).median / loop_no_csv.median);

  fragment.add(bench::figure("servo_plant_alone_x_realtime",
                             "Baseline: servo plant alone, RK4 at 8192 Hz, same commands", "x real time", plant_alone,
                             summary(plant_s.cpu_s)));

  char text[500];
  std::snprintf(text, sizeof text,
                "Paper SDOF: El Centro 1940 x 0.15 (40 s) + %.0f s free vibration = %.0f s, %lld steps at %.0f Hz, "
                "plant RK4 at %.0f Hz (%d substeps per step), central difference, phase lead 90 ms / a = 20; "
                "CSV of %.1f MB per run.",
                kPadSeconds, simulated_s, static_cast<long long>(first.steps_planned), scenario.control_rate_hz,
                servo.plant_rate_hz, substeps, static_cast<double>(csv_bytes) / 1e6);
  fragment.note(text);
  fragment.note(
      "Timed per trial: building the parts, every loop step, and draining the recorder (hybrid_test::TestAssembly, "
      "as `rpsd run` runs the test, no records kept in memory); not the reference run, criteria or plots of `rpsd "
      "run`. "
      "Headline: the writer thread drains the queue and writes nothing; the CSV figures format every row "
      "(27 numbers, printf %.10g) and write it to /dev/null or to a temporary file.");
  std::snprintf(text, sizeof text,
                "Loop against plant alone: loop and plant trials alternate (one untimed trial of each first); the "
                "ratio is the median over %d pairs of (plant time / loop time) = %.3f, interquartile %.3f-%.3f, "
                "min-max %.3f-%.3f; from the thread's CPU time instead (what waiting for a core does not "
                "change): %.3f, min-max %.3f-%.3f.",
                ratio.samples, ratio.median, ratio.p25, ratio.p75, ratio.min, ratio.max, cpu_ratio.median,
                cpu_ratio.min, cpu_ratio.max);
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "sdof_throughput: %s\n", e.what());
  return 1;
}
