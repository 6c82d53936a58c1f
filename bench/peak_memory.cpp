// Memory of a test against its length.
//
// (1) `rpsd run` end to end (test, reference, criteria, CSVs, plots) on 60 s of record (El
//     Centro + 20 s of free vibration) and on 30 minutes of a synthetic record (the shipped
//     synthetic-sdof scenario with its duration raised to 1800 s). The rpsd process's own
//     peak resident set (VmHWM, sampled from /proc every 20 ms while it runs, so gnuplot's
//     memory is not counted) and its wall time. The 30-minute peak exceeds the 60 s one by the
//     input record it holds (8 bytes per step, twice while its spectrum is computed).
// (2) In a fresh child process each: resident-set growth per simulated minute (peak less the
//     resident set once the scenario is loaded; the slope between a 1-minute run and a long
//     one) of the test and reference as `rpsd run` runs them (evaluated step by step, nothing
//     kept), up to 30 minutes; and, as the baseline, of the same two runs keeping every step
//     record and evaluated afterwards (how `rpsd run` worked before), up to 5 minutes.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_report.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/scenarios/study_file.h"

namespace {

using namespace rpsd;

// A "VmXXX:   1234 kB" line of /proc/<pid>/status, in MB; -1 when the process is gone.
double status_mb(const std::string& pid, const std::string& key) {
  std::ifstream in("/proc/" + pid + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1)) / 1024.0;
  }
  return -1.0;
}

struct Measured {
  double peak_mb = 0.0;           // the process's own VmHWM
  double with_children_mb = 0.0;  // wait4's ru_maxrss: the largest of it and its children
  double wall_s = 0.0;
};

Measured measure_rpsd_run(const std::filesystem::path& rpsd, const std::vector<std::string>& args) {
  std::vector<std::string> words{rpsd.string()};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const auto start = bench::Clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    if (!std::freopen("/dev/null", "w", stdout)) _exit(126);
    execv(argv[0], argv.data());
    _exit(127);
  }
  Measured m;
  const std::string id = std::to_string(pid);
  int status = 0;
  rusage usage{};
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0) throw std::runtime_error("wait4 failed");
    m.peak_mb = std::max(m.peak_mb, status_mb(id, "VmHWM"));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  m.wall_s = bench::seconds_since(start);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("rpsd run failed (" + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
  m.with_children_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  return m;
}

// Runs body in a fresh child process and returns the MB its resident set grew by, from
// after `prepare` to its peak.
double growth_in_child(const std::function<void()>& body, const std::function<void()>& prepare) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fds[0]);
    double growth = -1.0;
    try {
      prepare();
      const double base = status_mb("self", "VmRSS");
      body();
      growth = status_mb("self", "VmHWM") - base;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "peak_memory child: %s\n", e.what());
    }
    const std::string text = std::to_string(growth);
    if (write(fds[1], text.data(), text.size()) < 0) _exit(1);
    _exit(0);
  }
  close(fds[1]);
  char buffer[64] = {};
  const ssize_t n = read(fds[0], buffer, sizeof buffer - 1);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  const double growth = n > 0 ? std::atof(buffer) : -1.0;
  if (growth < 0.0) throw std::runtime_error("a measuring child failed");
  return growth;
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 1);
  std::filesystem::path rpsd = std::filesystem::path(RPSD_BENCH_RPSD);
  double long_minutes = 30.0, baseline_minutes = 5.0;
  for (std::size_t i = 0; i + 1 < options.rest.size(); i += 2) {
    if (options.rest[i] == "--rpsd")
      rpsd = options.rest[i + 1];
    else if (options.rest[i] == "--long-minutes")
      long_minutes = std::stod(options.rest[i + 1]);
    else if (options.rest[i] == "--baseline-minutes")
      baseline_minutes = std::stod(options.rest[i + 1]);
    else
      throw std::invalid_argument("unknown option " + options.rest[i]);
  }
  // Growth per minute is the difference to a 1-minute run over the minutes between.
  if (!(long_minutes > 1.0) || !(baseline_minutes > 1.0))
    throw std::invalid_argument("--long-minutes and --baseline-minutes: more than 1");
  bench::Fragment fragment("peak_memory", argc, argv);
  const auto work = std::filesystem::temp_directory_path() / ("rpsd-bench-memory-" + std::to_string(getpid()));
  std::filesystem::create_directories(work);
  const std::string long_seconds = std::to_string(static_cast<long>(long_minutes * 60.0));
  const auto elcentro = (options.source_dir / "examples/scenarios/elcentro-sdof.yaml").string();
  const auto synthetic = (options.source_dir / "examples/scenarios/synthetic-sdof.yaml").string();

  // (1) rpsd run end to end.
  std::vector<double> short_peaks, short_children, short_walls;
  for (int i = 0; i < options.repetitions; ++i) {
    const Measured m = measure_rpsd_run(rpsd, {"run", elcentro, "--set", "ground_motion.pad_after_s=20", "--out",
                                               (work / ("60s-" + std::to_string(i))).string()});
    short_peaks.push_back(m.peak_mb);
    short_children.push_back(m.with_children_mb);
    short_walls.push_back(m.wall_s);
  }
  const Measured long_run =
      measure_rpsd_run(rpsd, {"run", synthetic, "--set", "ground_motion.synthetic.duration_s=" + long_seconds, "--out",
                              (work / "long").string()});
  std::filesystem::remove_all(work);

  // (2) growth per simulated minute, in fresh child processes: the difference between a
  // short and a long run, so that fixed costs (threads, queues, buffers) cancel.
  const auto growth = [&](double minutes, bool keep_records) {
    studies::StudyDocument file;
    return growth_in_child(
        [&] {
          const auto& s = std::get<hybrid_test::TestConfig>(file.study);
          if (keep_records) {
            const auto test = hybrid_test::run_test(s, "/dev/null", false);
            const auto reference = hybrid_test::run_test(s, "/dev/null", true);
            hybrid_test::evaluate(s, test, reference);
          } else {
            hybrid_test::run_test_and_reference(s, "/dev/null", "/dev/null");
          }
        },
        [&] {
          file = scenarios::load_study(synthetic, {scenarios::parse_override("ground_motion.synthetic.duration_s=" +
                                                                             std::to_string(minutes * 60.0))});
        });
  };
  constexpr double kShortMinutes = 1.0;
  const double streamed_per_min =
      (growth(long_minutes, false) - growth(kShortMinutes, false)) / (long_minutes - kShortMinutes);
  const double kept_per_min =
      (growth(baseline_minutes, true) - growth(kShortMinutes, true)) / (baseline_minutes - kShortMinutes);

  const bench::Figure a =
      bench::figure("peak_rss_60s_mb", "Peak memory, `rpsd run` of 60 s (El Centro + 20 s), rpsd process", "MB",
                    bench::summarize(short_peaks));
  fragment.add(a);

  fragment.add(bench::figure("peak_rss_30min_mb",
                             "Peak memory, `rpsd run` of " + long_seconds + " s (synthetic record), rpsd process", "MB",
                             bench::single(long_run.peak_mb))
                   .against("peak_rss_60s_mb", "long run / 60 s run", long_run.peak_mb / a.value.median));

  // Flat: what a step leaves behind is below a byte (a kept record is about 860 bytes).
  fragment.add(
      bench::figure("rss_growth_mb_per_min",
                    "Memory growth per simulated minute, as `rpsd run` runs (test + reference)", "MB/min",
                    bench::single(streamed_per_min))
          .against("rss_growth_kept_records_mb_per_min", "streamed / records kept", streamed_per_min / kept_per_min)
          .aiming_for("flat (< 0.01 MB/min)", streamed_per_min < 0.01));

  fragment.add(bench::figure("rss_growth_kept_records_mb_per_min",
                             "Baseline: the same keeping every step record (rpsd run before this change)", "MB/min",
                             bench::single(kept_per_min)));

  fragment.add(bench::figure("rpsd_run_60s_wall_s",
                             "Wall time, `rpsd run` of 60 s end to end (test, reference, CSVs, plots)", "s",
                             bench::summarize(short_walls)));

  fragment.add(bench::figure("rpsd_run_30min_wall_s", "Wall time, `rpsd run` of " + long_seconds + " s end to end", "s",
                             bench::single(long_run.wall_s)));

  char text[1000];
  std::snprintf(text, sizeof text,
                "Largest resident set including gnuplot children (wait4): %.0f MB for 60 s, %.0f MB for %s s. "
                "The long run's peak exceeds the 60 s one by the record it holds (8 bytes per step) and, while the "
                "response spectrum is computed before the test, a copy of it. "
                "Growth per minute: (growth over the long run - growth over 1 min) / the minutes between, growth being "
                "the peak resident set less the resident set with the scenario loaded, in a fresh process; the record "
                "itself (8 bytes per step, %.0f MB for %s s at 1024 Hz) is loaded before.",
                bench::summarize(short_children).median, long_run.with_children_mb, long_seconds.c_str(),
                8.0 * 1024.0 * long_minutes * 60.0 / 1e6, long_seconds.c_str());
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "peak_memory: %s\n", e.what());
  return 1;
}
