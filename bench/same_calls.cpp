// Calls that exist unchanged since before the performance work (commit 50b1d9d), so that the
// same file, compiled against an older checkout's libraries, gives the "before" figures:
// run_test(scenario, csv, false) as `rpsd run` then ran its test (every record kept), with the
// CSV formatted to /dev/null and without CSV; the servo plant alone on the same commands; and
// the Figure 8 sweep. Median of N trials (default 9), wall clock and thread CPU time.
// Usage: same_calls SOURCE_DIR [TRIALS]. Not part of bench/run-all.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "rpsd/coordinator/delay_compensation_study.h"
#include "rpsd/coordinator/test_runner.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/servo_hydraulic_plant.h"

namespace {

double cpu() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
double wall() { timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
template <class F> void trial(const char* what, int n, double sim, F f) {
  std::vector<double> w, c;
  f();
  for (int i = 0; i < n; ++i) { double w0 = wall(), c0 = cpu(); f(); w.push_back(wall() - w0); c.push_back(cpu() - c0); }
  std::sort(w.begin(), w.end()); std::sort(c.begin(), c.end());
  std::printf("%-34s wall median %7.1f ms (%6.0fx real time, min %.1f max %.1f ms), thread CPU %7.1f ms (%6.0fx)\n", what,
              1e3 * w[n / 2], sim / w[n / 2], 1e3 * w.front(), 1e3 * w.back(), 1e3 * c[n / 2], sim / c[n / 2]);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: same_calls SOURCE_DIR [TRIALS]\n");
    return 2;
  }
  using namespace rpsd;
  const int n = argc > 2 ? std::atoi(argv[2]) : 9;
  const auto file = scenarios::load_study(std::string(argv[1]) + "/examples/scenarios/elcentro-sdof.yaml", {scenarios::parse_override("ground_motion.pad_after_s=20")});
  const auto& s = std::get<scenarios::TestScenario>(file.study);
  const double sim = s.duration_s;
  const auto first = coordinator::run_test(s, {}, false);
  trial("run_test, CSV to /dev/null", n, sim, [&] { coordinator::run_test(s, "/dev/null", false); });
  trial("run_test, no CSV", n, sim, [&] { coordinator::run_test(s, {}, false); });
  servo::ServoHydraulicPlant plant(std::get<servo::ServoSystemParameters>(s.plant));
  double sink = 0;
  trial("plant alone, same commands", n, sim, [&] {
    plant.reset(0.0); double prev = 0;
    for (const auto& r : first.records) { plant.advance(prev, r.command_m[0], 1.0 / 1024); prev = r.command_m[0]; sink += plant.measure().displacement_m; }
  });
  std::printf("(%g, %zu steps)\n", sink, first.records.size());
  const auto f8 = std::get<scenarios::DelayCompensationStudy>(scenarios::load_study(std::string(argv[1]) + "/examples/scenarios/paper-fig8-delay-compensation.yaml").study);
  trial("Figure 8 sweep (10 cases; 62 s sim)", n, 62.0, [&] { coordinator::run_delay_compensation(f8); });
}
