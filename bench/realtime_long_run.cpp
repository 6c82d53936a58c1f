// The long run: a 30-minute real-time test at 1024 Hz against a simulated servo node over
// Cyclone DDS on loopback, with the resident memory of both processes sampled throughout.
//
// `rpsd servo-node examples/nodes/bridge-pier-site-1.yaml` (real time, its paper servo model)
// and `rpsd run examples/scenarios/synthetic-sdof.yaml` over DDS in real time with the synthetic record
// lengthened to `--minutes` (and any `--set KEY=VALUE` given, passed on to rpsd run). Every second: VmRSS of the
// coordinator and of the node, and the size of time_history.csv (the test is running while it grows). Afterwards: the
// run's summary.json, every row of time_history.csv (one per planned step, steps in order, none missing) and the node's
// --summary.
//
// Memory is "flat" when the least-squares slope of each process's resident set over the run,
// from its second minute on (--warmup-seconds; the first holds Cyclone's discovery and the histograms' first
// touch), is below one 4 KiB page per minute (a fall, memory handed back, is not growth). The run's own stop rule is
// clock.max_feedback_age_periods: its default (4 periods) is the safety setting for hardware;
// this VM stalls for up to 0.4 s (cyclictest), so the long run takes --max-feedback-age
// (default 1000 periods, 0.98 s at 1024 Hz; the most the key allows) and reports how many steps ran on old feedback and
// how old.
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_report.h"
#include "child_process.h"
#include "rpsd/studies/line_fit.h"

namespace {

using namespace rpsd;
using nlohmann::json;

// A number of /proc/PID/status ("VmRSS" in KiB, "Threads"), or -1 once the process is gone.
double status_of(pid_t pid, const std::string& key) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1));
  }
  return -1.0;
}

std::uintmax_t size_or_zero(const std::filesystem::path& file) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  return ec ? 0 : size;
}

struct Sample {
  double t_s = 0.0;
  double coordinator_kib = -1.0, node_kib = -1.0;
  double coordinator_threads = -1.0, node_threads = -1.0;
  std::uintmax_t history_bytes = 0;
};

// Where a process's resident set rose during the test: how often and by how much in all.
struct Rises {
  int count = 0;
  double total_kib = 0.0, largest_kib = 0.0, largest_at_min = 0.0;
  void see(double before, double after, double at_min) {
    if (after <= before) return;
    ++count;
    total_kib += after - before;
    if (after - before > largest_kib) {
      largest_kib = after - before;
      largest_at_min = at_min;
    }
  }
};

// What time_history.csv holds: rows, whether the steps run 1, 2, 3, ... without a gap, and
// the feedback ages (column feedback_age_periods).
struct History {
  std::int64_t rows = 0;
  bool steps_in_order = true;
  std::int64_t first_gap_at = -1;
  int max_feedback_age = 0;
  std::int64_t rows_on_old_feedback = 0;
};

History read_history(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": missing");
  std::string line;
  std::getline(in, line);
  // The header names the columns: find "step" and "feedback_age_periods".
  int step_col = -1, age_col = -1, col = 0;
  for (std::size_t start = 0; start <= line.size(); ++col) {
    const std::size_t end = std::min(line.find(',', start), line.size());
    const std::string name = line.substr(start, end - start);
    if (name == "step") step_col = col;
    if (name == "feedback_age_periods") age_col = col;
    start = end + 1;
  }
  if (step_col < 0 || age_col < 0) throw std::runtime_error(file.string() + ": no step or feedback_age_periods column");
  History h;
  while (std::getline(in, line)) {
    long long step = -1;
    int age = -1;
    col = 0;
    for (std::size_t start = 0; start <= line.size() && (step < 0 || age < 0); ++col) {
      const std::size_t end = std::min(line.find(',', start), line.size());
      if (col == step_col) std::from_chars(line.data() + start, line.data() + end, step);
      if (col == age_col) std::from_chars(line.data() + start, line.data() + end, age);
      start = end + 1;
    }
    if (step != h.rows + 1 && h.steps_in_order) {  // steps count from 1
      h.steps_in_order = false;
      h.first_gap_at = h.rows;
    }
    h.max_feedback_age = std::max(h.max_feedback_age, age);
    if (age > 0) ++h.rows_on_old_feedback;
    ++h.rows;
  }
  return h;
}

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[200];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 1);
  std::string rpsd = RPSD_BENCH_RPSD;
  double minutes = 30.0;
  int rate = 1024, domain = 93, max_age = 1000;
  // The start of the test left out of the slope (Cyclone's discovery, the histograms' first
  // touch). Shorter only for bench/run-all --smoke, whose slope says nothing but must exist.
  double warmup_s = 60.0;
  bool keep = false;
  std::vector<std::string> extra_settings;  // --set KEY=VALUE for rpsd run, in order
  for (std::size_t i = 0; i + 1 < options.rest.size(); i += 2) {
    const std::string& key = options.rest[i];
    const std::string& value = options.rest[i + 1];
    if (key == "--rpsd")
      rpsd = value;
    else if (key == "--minutes")
      minutes = std::stod(value);
    else if (key == "--warmup-seconds")
      warmup_s = std::stod(value);
    else if (key == "--rate")
      rate = std::stoi(value);
    else if (key == "--domain")
      domain = std::stoi(value);
    else if (key == "--max-feedback-age")
      max_age = std::stoi(value);
    else if (key == "--keep")
      keep = value == "1";
    else if (key == "--set")
      extra_settings.push_back(value);
    else
      throw std::invalid_argument("unknown option " + key);
  }
  if (options.rest.size() % 2 != 0) throw std::invalid_argument("unknown option " + options.rest.back());
  if (!(warmup_s >= 0.0)) throw std::invalid_argument("--warmup-seconds: not negative");
  if (60.0 * minutes < warmup_s + 10.0) {
    throw std::invalid_argument("--minutes: at least --warmup-seconds + 10 s (the warm-up is not part of the slope)");
  }
  bench::Fragment fragment("realtime_long_run", argc, argv);
  bench::install_stop_handlers();
  const auto work = std::filesystem::temp_directory_path() / ("rpsd-bench-long-" + std::to_string(getpid()));
  const auto out = work / "run";
  std::filesystem::create_directories(work);
  const auto src = std::filesystem::absolute(options.source_dir);
  const std::string r = std::to_string(rate), d = std::to_string(domain);
  // A test id of its own: the system tests run test 7 on domains 1-200, and partitions by
  // test id keep a test that shares the domain apart.
  const std::string test_id = "9301";
  const double seconds = 60.0 * minutes;

  bench::ChildProcess node({rpsd, "servo-node", (src / "examples/nodes/bridge-pier-site-1.yaml").string(), "--set",
                            "node.mode=real_time", "--set", "node.control_rate_hz=" + r, "--set", "dds.domain_id=" + d,
                            "--set", "node.test_id=" + test_id, "--summary", (work / "node.json").string()},
                           {}, work / "node.log");
  std::vector<std::string> run_argv{rpsd,
                                    "run",
                                    (src / "examples/scenarios/synthetic-sdof.yaml").string(),
                                    "--out",
                                    out.string(),
                                    "--set",
                                    "transport={kind: dds, test_id: " + test_id + ", domain_id: " + d +
                                        ", dds_config: " + (src / "transport/config/loopback.xml").string() + "}",
                                    "--set",
                                    "clock.mode=real_time",
                                    "--set",
                                    "clock.control_rate_hz=" + r,
                                    "--set",
                                    "clock.max_feedback_age_periods=" + std::to_string(max_age),
                                    "--set",
                                    "ground_motion.synthetic.duration_s=" + format("%g", seconds)};
  std::string extra_note;
  for (const std::string& setting : extra_settings) {
    run_argv.insert(run_argv.end(), {"--set", setting});
    extra_note += " --set " + setting;
  }
  bench::ChildProcess run(run_argv, {}, work / "run.log");
  std::vector<Sample> samples;
  const auto start = bench::Clock::now();
  int code = -1;
  // The paced test, then the plots; discovery may take 20 s.
  while ((code = run.wait_for(1.0)) < 0 && run.running()) {
    if (bench::seconds_since(start) > seconds + 600.0) {
      run.stop(SIGTERM, 10.0);
      fragment.note("the run had not ended 10 minutes after its record: stopped");
      break;
    }
    samples.push_back({bench::seconds_since(start), status_of(run.pid(), "VmRSS"), status_of(node.pid(), "VmRSS"),
                       status_of(run.pid(), "Threads"), status_of(node.pid(), "Threads"),
                       size_or_zero(out / "time_history.csv")});
  }
  node.stop(SIGTERM, 10.0);
  const std::string run_log = bench::read_text(work / "run.log");
  std::fprintf(stderr, "realtime_long_run: exit %d\n%s", code, run_log.c_str());

  // The test's samples: those after which time_history.csv still grew (the test was running
  // when they were taken; afterwards `rpsd run` builds the reference run), from its second
  // minute on.
  std::vector<double> t_min, coord, nodes;
  double test_start = -1.0, coord_first = 0, node_first = 0, coord_peak = 0, node_peak = 0;
  Rises coord_rises, node_rises;
  double threads_first = -1, threads_max = 0;
  for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
    const Sample& s = samples[i];
    if (samples[i + 1].history_bytes <= s.history_bytes || s.history_bytes == 0 || s.coordinator_kib < 0 ||
        s.node_kib < 0)
      continue;
    if (test_start < 0) test_start = s.t_s;
    if (s.t_s - test_start < warmup_s) continue;
    const double at_min = (s.t_s - test_start) / 60.0;
    if (t_min.empty()) {
      coord_first = s.coordinator_kib;
      node_first = s.node_kib;
      threads_first = s.coordinator_threads;
    } else {
      coord_rises.see(coord.back(), s.coordinator_kib, at_min);
      node_rises.see(nodes.back(), s.node_kib, at_min);
    }
    threads_max = std::max(threads_max, s.coordinator_threads);
    t_min.push_back(at_min);
    coord.push_back(s.coordinator_kib);
    nodes.push_back(s.node_kib);
    coord_peak = std::max(coord_peak, s.coordinator_kib);
    node_peak = std::max(node_peak, s.node_kib);
  }
  {
    std::ofstream rss(work / "rss.txt");
    rss << "t_s coordinator_kib node_kib coordinator_threads node_threads time_history_bytes\n";
    for (const auto& s : samples) {
      rss << s.t_s << ' ' << s.coordinator_kib << ' ' << s.node_kib << ' ' << s.coordinator_threads << ' '
          << s.node_threads << ' ' << s.history_bytes << '\n';
    }
  }

  const bool have_summary = std::filesystem::exists(out / "summary.json");
  json summary = have_summary ? json::parse(std::ifstream(out / "summary.json")) : json::object();
  const bool completed = summary.value("completed", false);
  const auto planned = summary.value("steps_planned", std::int64_t{0});
  const History history =
      std::filesystem::exists(out / "time_history.csv") ? read_history(out / "time_history.csv") : History{};
  const bool every_step = completed && history.rows == planned && history.steps_in_order &&
                          summary.value("dropped_records", std::uint64_t{1}) == 0;
  constexpr double kPageKiB = 4.0;
  const double coord_slope = studies::least_squares_slope(t_min, coord),
               node_slope = studies::least_squares_slope(t_min, nodes);
  const std::string status =
      completed ? "completed"
                : "DID NOT COMPLETE: " + summary.value("outcome", std::string("exit " + std::to_string(code)));

  bench::Figure runs = bench::figure(
      "long_run_completed", format("%g-minute real-time run at ", minutes) + r + " Hz over DDS (" + status + ")",
      "steps recorded", bench::single(static_cast<double>(history.rows)));
  runs.aiming_for("every planned step (" + std::to_string(planned) + ") recorded, in order", every_step);
  fragment.add(runs);
  const std::string from = format("from %g s into the test on", warmup_s);
  if (!t_min.empty()) {
    fragment.add(bench::figure("long_run_rss_slope_coordinator_kib_per_min",
                               "  coordinator resident set growth (least squares, " + from + ")", "KiB/min",
                               bench::single(coord_slope))
                     .aiming_for("< 4 KiB/min (flat)", coord_slope < kPageKiB));
    fragment.add(bench::figure("long_run_rss_slope_node_kib_per_min",
                               "  servo node resident set growth (least squares, " + from + ")", "KiB/min",
                               bench::single(node_slope))
                     .aiming_for("< 4 KiB/min (flat)", node_slope < kPageKiB));
    fragment.add(bench::figure("long_run_rss_coordinator_mib", "  coordinator resident set, peak during the test",
                               "MiB", bench::single(coord_peak / 1024.0)));
    fragment.add(bench::figure("long_run_rss_node_mib", "  servo node resident set, peak during the test", "MiB",
                               bench::single(node_peak / 1024.0)));
    fragment.add(bench::figure("long_run_rss_change_coordinator_kib",
                               "  coordinator resident set, end of the test less " + format("%g s in", warmup_s), "KiB",
                               bench::single(coord.back() - coord_first)));
    fragment.note(format("Resident sets %g s in and at the end", warmup_s) +
                  format(" of the test: coordinator %.0f", coord_first) + format(" -> %.0f KiB, ", coord.back()) +
                  format("node %.0f", node_first) + format(" -> %.0f KiB; ", nodes.back()) +
                  std::to_string(t_min.size()) + " one-second samples. Rises: coordinator " +
                  std::to_string(coord_rises.count) +
                  format(" (%.0f KiB in all, the largest %.0f KiB", coord_rises.total_kib, coord_rises.largest_kib) +
                  format(" at minute %.1f), node ", coord_rises.largest_at_min) + std::to_string(node_rises.count) +
                  format(" (%.0f KiB in all); coordinator threads %.0f", node_rises.total_kib, threads_first) +
                  format(" at the end of the warm-up, at most %.0f.", threads_max));
  }
  if (have_summary) {
    const json& t = summary["timing"];
    const auto cycles = t.value("cycles", std::int64_t{0});
    fragment.add(bench::figure(
        "long_run_late_feedback_pct", "  steps run on old feedback (late feedback)", "% of cycles",
        bench::single(cycles > 0 ? 100.0 * static_cast<double>(t.value("late_feedback", std::int64_t{0})) /
                                       static_cast<double>(cycles)
                                 : 0.0)));
    fragment.add(bench::figure("long_run_max_feedback_age_periods", "  oldest feedback a step ran on",
                               "control periods", bench::single(history.max_feedback_age)));
    fragment.note(std::to_string(history.rows) + " rows of " + std::to_string(planned) + " planned steps" +
                  (history.steps_in_order ? ", steps in order without a gap"
                                          : ", first gap at row " + std::to_string(history.first_gap_at)) +
                  "; " + std::to_string(history.rows_on_old_feedback) + " rows on old feedback, oldest " +
                  std::to_string(history.max_feedback_age) + " periods; coordinator " +
                  std::to_string(t.value("overruns", 0)) + " overruns of " + std::to_string(cycles) +
                  " cycles, jitter p99 " + format("%.1f us", 1e6 * t["jitter"].value("p99_s", 0.0)) + ", max " +
                  format("%.1f ms", 1e3 * t["jitter"].value("max_s", 0.0)) +
                  (t.value("sched_fifo", false) ? "" : ", no SCHED_FIFO") + ".");
  }
  if (std::filesystem::exists(work / "node.json")) {
    const json n = json::parse(std::ifstream(work / "node.json"));
    fragment.note("Node: " + std::to_string(n.value("cycles", std::int64_t{0})) + " cycles, " +
                  std::to_string(n.value("overruns", std::int64_t{0})) + " overruns, " +
                  std::to_string(n.value("missed_periods", std::int64_t{0})) + " missed periods, " +
                  std::to_string(n.value("holds", std::int64_t{0})) + " holds" +
                  (n.value("faulted", false) ? ", FAULTED" : "") + ".");
  }
  fragment.note(
      "rpsd servo-node examples/nodes/bridge-pier-site-1.yaml (real time at " + r +
      " Hz, the paper's servo model at its own "
      "rate) and rpsd run examples/scenarios/synthetic-sdof.yaml over DDS on loopback (transport/config/loopback.xml) "
      "in real time at " +
      r + " Hz, " + format("%g", minutes) + " minutes of the synthetic record, clock.max_feedback_age_periods = " +
      std::to_string(max_age) + " (the default 4 is the hardware safety setting; this VM stalls for up to 0.4 s)" +
      (extra_note.empty() ? "" : "; also" + extra_note) +
      ". "
      "Memory: VmRSS every second while time_history.csv grew; the slope is fitted " +
      from + ".");
  if (keep)
    std::fprintf(stderr, "realtime_long_run: kept %s\n", work.c_str());
  else
    std::filesystem::remove_all(work);
  fragment.write(options.out);
  // A run that never started (bad input, discovery) measured nothing: the step fails.
  if (!have_summary) {
    std::fprintf(stderr, "realtime_long_run: the run wrote no summary (see above)\n");
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "realtime_long_run: %s\n", e.what());
  return 1;
}
