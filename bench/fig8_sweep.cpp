// The seed paper's Figure 8 study as `rpsd run examples/scenarios/paper-fig8-delay-compensation.yaml`
// runs it (studies::run_delay_compensation): ten RPsD free-vibration tests of the
// paper's SDOF on the full servo model, one per compensated delay, each with its delay
// theory and damping identification. Timed: the whole sweep, without CSV files or plots.
// Figures: cases per second, and simulated seconds per wall second (cases that go unstable
// stop early at 10 times the initial displacement, so they simulate less than 8 s).
// Baseline in the same run: the same sweep on the ideal-delay actuator
// (examples/scenarios/paper-fig8-ideal-delay.yaml), which has no plant dynamics to integrate.
#include <cstdio>
#include <stdexcept>

#include "bench_report.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/studies/delay_compensation_study.h"

namespace {

using namespace rpsd;

struct Sweep {
  studies::DelayCompensationStudy study;
  double simulated_s = 0.0;
  bench::Trials seconds;
};

Sweep time_sweep(const std::filesystem::path& file, int repetitions) {
  Sweep s;
  s.study = std::get<studies::DelayCompensationStudy>(scenarios::load_study(file).study);
  for (const auto& c : studies::run_delay_compensation(s.study)) {
    s.simulated_s += static_cast<double>(c.steps) / s.study.control_rate_hz;
  }
  s.seconds = bench::time_trials(repetitions, 0, [&] {
    if (studies::run_delay_compensation(s.study).size() != s.study.compensated_delays_s.size()) {
      throw std::runtime_error("a case is missing");
    }
  });
  return s;
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 7);
  bench::Fragment fragment("fig8_sweep", argc, argv);
  const Sweep servo =
      time_sweep(options.source_dir / "examples/scenarios/paper-fig8-delay-compensation.yaml", options.repetitions);
  const Sweep ideal =
      time_sweep(options.source_dir / "examples/scenarios/paper-fig8-ideal-delay.yaml", options.repetitions);

  const auto cases = static_cast<double>(servo.study.compensated_delays_s.size());
  const auto per_second = [&](const bench::Trials& t, double count) {
    return std::pair{bench::map_summary(bench::summarize(t.wall_s), [=](double s) { return count / s; }),
                     bench::map_summary(bench::summarize(t.cpu_s), [=](double s) { return count / s; })};
  };
  const auto [servo_cases, servo_cases_cpu] = per_second(servo.seconds, cases);
  const auto [ideal_cases, ideal_cases_cpu] =
      per_second(ideal.seconds, static_cast<double>(ideal.study.compensated_delays_s.size()));
  const auto [servo_realtime, servo_realtime_cpu] = per_second(servo.seconds, servo.simulated_s);

  fragment.add(bench::figure("fig8_sweep_cases_per_s", "Figure 8 sweep (10 cases, servo model), cases per second",
                             "cases/s", servo_cases, servo_cases_cpu)
                   .against("fig8_ideal_delay_cases_per_s", "servo model / ideal delay (speed)",
                            servo_cases.median / ideal_cases.median));

  fragment.add(bench::figure("fig8_sweep_x_realtime", "  the same, simulated time per wall time", "x real time",
                             servo_realtime, servo_realtime_cpu));

  fragment.add(bench::figure("fig8_ideal_delay_cases_per_s",
                             "Baseline: the same sweep on the ideal 75 ms delay actuator", "cases/s", ideal_cases,
                             ideal_cases_cpu));

  char text[300];
  std::snprintf(text, sizeof text,
                "Servo-model sweep: %.0f cases, %.1f s simulated in all (8 s each, unstable cases stop early), "
                "1024 Hz control, plant RK4 at 8192 Hz; no CSV or plots; one thread.",
                cases, servo.simulated_s);
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "fig8_sweep: %s\n", e.what());
  return 1;
}
