// Real-time overruns of distributed tests across two hosts: the coordinator in one network
// namespace, the servo nodes in another, joined by a veth pair (198.18.0.1 and 198.18.0.2),
// Cyclone's lab-LAN profile (transport/config/lab-lan.xml) on eth0 with unicast discovery.
// bench/realtime-overruns makes the namespaces, runs this, and removes them.
//
// For each control rate, first the host's floor (the empty paced loop of realtime/host_floor.h,
// as `rpsd host-check` measures it, CPUs kept awake) and ddsperf on the same link, then each
// configuration of kConfigurations that runs at the rate: its `rpsd servo-node` processes
// (real_time, node.control_rate_hz = the rate) and `rpsd run SCENARIO` in real time at the rate
// for `--seconds` of record, all with SCHED_FIFO 80 and locked memory as the files ask. Read
// afterwards: the run's summary.json (each Monte Carlo run's, where it has runs: timing.cycles,
// overruns, late_feedback, round trip per site, outcome) and each node's --summary (cycles,
// overruns, missed periods, holds). Each configuration's overruns are reported against the
// floor measured minutes before at the same rate.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_report.h"
#include "child_process.h"
#include "ddsperf.h"
#include "rpsd/realtime/cpu_wake_latency.h"
#include "rpsd/realtime/host_floor.h"
#include "rpsd/realtime/kernel_preemption.h"
#include "rpsd/realtime/realtime_setup.h"

namespace {

using namespace rpsd;
using nlohmann::json;

// One servo-node process of a configuration: its file (under the source tree) and overrides
// beyond those every node gets (mode, rate, DDS configuration and domain).
struct NodeProcess {
  std::string file;
  std::vector<std::string> sets;
};

// One test the step runs in real time at each of its rates.
struct Configuration {
  std::string tag;                // in the figures' ids after their kind ("" for the two-site bridge, the first)
  std::string name;               // in titles and notes
  std::string scenario;           // under the source tree
  std::vector<std::string> sets;  // the coordinator's overrides beyond those every run gets
  std::vector<NodeProcess> nodes;
  std::vector<int> rates;  // empty: every rate of --rates
  // The part of the scenario's record a run starts at, and the record's end: a run takes
  // `seconds` from the start, then free vibration if the record ends before.
  double record_start_s = 0.0, record_end_s = 0.0;
};

// The node file's one-channel lists (initial displacement, each limit) given for two channels:
// the node serving both piers of the bridge on one site, each with pier 1's rig and limits.
std::vector<std::string> as_two_channels(const std::filesystem::path& node_file) {
  const YAML::Node root = YAML::LoadFile(node_file.string());
  std::vector<std::string> sets{"actuator.channels=2"};
  const auto twice = [&](const std::string& key, const YAML::Node& list) {
    if (!list.IsSequence() || list.size() != 1)
      throw std::runtime_error(node_file.string() + ": " + key + ": expected a list of one value");
    const std::string v = list[0].as<std::string>();
    sets.push_back(key + "=[" + v + ", " + v + "]");
  };
  twice("actuator.initial_displacement_m", root["actuator"]["initial_displacement_m"]);
  for (const auto& entry : root["limits"]) {
    if (entry.second.IsSequence()) twice("limits." + entry.first.as<std::string>(), entry.second);
  }
  return sets;
}

std::vector<Configuration> configurations(const std::filesystem::path& src) {
  const std::string pier = "examples/nodes/bridge-pier-site-";
  // The RTHS benchmark's record: 5 s of zeros, the motion, 5 s of zeros (41.18 s in all).
  return {
      {"",
       "two-site bridge, 2 nodes",
       "examples/scenarios/two-site-bridge.yaml",
       {},
       {{pier + "1.yaml", {}}, {pier + "2.yaml", {}}},
       {},
       0.0,
       40.0},
      // Both piers on site 1: one node process with two channels.
      {"one_site_",
       "bridge on one site, 1 node",
       "examples/scenarios/two-site-bridge.yaml",
       {"experimental.1.site=1"},
       {{pier + "1.yaml", as_two_channels(src / (pier + "1.yaml"))}},
       {},
       0.0,
       40.0},
      // The benchmark's plant (PI controller, converters, noise) in the node at 4096 Hz, the
      // benchmark's rate. Two Monte Carlo runs, the fewest the file's section allows; their
      // cycles are pooled.
      {"rths_",
       "RTHS benchmark plant (PI, converters), 1 node",
       "examples/scenarios/rths-benchmark-sample-controller-case-1.yaml",
       {"monte_carlo.runs=2"},
       {{"examples/nodes/rths-benchmark-site.yaml", {}}},
       {4096},
       5.0,
       41.18},
  };
}

std::string loadavg() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": missing");
  return json::parse(in);
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[200];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// The empty paced loop at `rate_hz` (host_floor.h, the code of rpsd host-check and
// bench/realtime_floor), SCHED_FIFO 80, locked memory and the CPUs kept awake as rpsd's loops
// ask, on a thread of its own so that the processes this step starts later inherit no
// real-time policy from it. `refused`: what the OS refused of that.
realtime::EmptyLoopFloor measure_floor(int rate_hz, double seconds, std::string& refused) {
  realtime::EmptyLoopFloor floor;
  std::exception_ptr error;
  std::thread thread([&] {
    try {
      realtime::RealTimeRequest request;
      request.keep_cpus_awake = false;  // held below, for the loop only
      refused = realtime::apply_realtime(request).refused;
      const realtime::CpuWakeLatencyHold awake(0);
      if (!awake.held()) refused += "keeping the CPUs awake refused: " + awake.refused();
      floor = realtime::measure_empty_loop(rate_hz, seconds, awake.held());
    } catch (...) {
      error = std::current_exception();
    }
  });
  thread.join();
  if (error) std::rethrow_exception(error);
  return floor;
}

// What one configuration's run at one rate measured, pooled over its Monte Carlo runs.
struct RunFigures {
  bool completed = true;
  std::string outcome;
  std::int64_t cycles = 0, overruns = 0, late = 0, skipped = 0, steps = 0, steps_planned = 0;
  std::vector<double> p50_us, p99_us, max_us;  // the worse site's, one per run
  double jitter_p99_s = 0.0, jitter_max_s = 0.0;
  bool sched_fifo = true, cpus_awake = true;
  std::string refused;
};

// The run's summary.json, or each of its runs' where it has runs (a Monte Carlo scenario).
RunFigures read_run(const std::filesystem::path& dir) {
  const json top = read_json(dir / "summary.json");
  std::vector<json> runs;
  if (top.contains("runs")) {
    for (const auto& r : top["runs"]) {
      const auto file = dir / r.value("folder", std::string()) / "summary.json";
      if (std::filesystem::exists(file)) runs.push_back(read_json(file));
    }
    if (runs.empty()) throw std::runtime_error((dir / "summary.json").string() + ": no run wrote a summary");
  } else {
    runs.push_back(top);
  }
  RunFigures r;
  for (const json& s : runs) {
    const json& t = s["timing"];
    r.cycles += t.value("cycles", std::int64_t{0});
    r.overruns += t.value("overruns", std::int64_t{0});
    r.late += t.value("late_feedback", std::int64_t{0});
    r.skipped += t.value("skipped_deadlines", std::int64_t{0});
    r.steps += s.value("steps", std::int64_t{0});
    r.steps_planned += s.value("steps_planned", std::int64_t{0});
    if (!s.value("completed", false)) {
      r.completed = false;
      r.outcome += (r.outcome.empty() ? "" : "; ") + s.value("outcome", std::string("?"));
    }
    r.jitter_p99_s = std::max(r.jitter_p99_s, t["jitter"].value("p99_s", 0.0));
    r.jitter_max_s = std::max(r.jitter_max_s, t["jitter"].value("max_s", 0.0));
    r.sched_fifo = r.sched_fifo && t.value("sched_fifo", false);
    r.cpus_awake = r.cpus_awake && t.value("cpus_kept_awake", false);
    if (!t.value("refused", std::string()).empty()) r.refused = t.value("refused", std::string());
    double p50 = 0.0, p99 = 0.0, max = 0.0;
    for (const auto& site : t["sites"]) {
      p50 = std::max(p50, 1e6 * site["round_trip"].value("p50_s", 0.0));
      p99 = std::max(p99, 1e6 * site["round_trip"].value("p99_s", 0.0));
      max = std::max(max, 1e6 * site["round_trip"].value("max_s", 0.0));
    }
    if (!t["sites"].empty()) {
      r.p50_us.push_back(p50);
      r.p99_us.push_back(p99);
      r.max_us.push_back(max);
    }
  }
  return r;
}

// The nodes' --summary files: the worse node's overruns (% of its cycles) and a line per node.
double read_nodes(const std::vector<std::filesystem::path>& files, std::string& text) {
  double worst = 0.0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string which = " node " + std::to_string(i + 1) + ": ";
    if (!std::filesystem::exists(files[i])) {
      text += which + "no summary;";
      continue;
    }
    const json n = read_json(files[i]);
    const auto cycles = n.value("cycles", std::int64_t{0});
    const auto overruns = n.value("overruns", std::int64_t{0});
    if (cycles > 0) worst = std::max(worst, 100.0 * static_cast<double>(overruns) / static_cast<double>(cycles));
    text += which + std::to_string(overruns) + " overruns of " + std::to_string(cycles) + " cycles, " +
            std::to_string(n.value("missed_periods", std::int64_t{0})) + " missed periods, " +
            std::to_string(n.value("holds", std::int64_t{0})) + " holds, jitter p99 " +
            format("%.1f us", 1e6 * n["jitter"].value("p99_s", 0.0)) + (n.value("faulted", false) ? ", FAULTED" : "") +
            (n.value("sched_fifo", false) ? "" : ", no SCHED_FIFO") +
            (n.value("cpus_kept_awake", false) ? "" : ", CPUs free to idle") + ";";
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 1);
  std::string rpsd = RPSD_BENCH_RPSD, coord_ns, node_ns;
  std::vector<int> rates{1024, 2048, 4096};
  double seconds = 60.0;
  double floor_seconds = 0.0;  // 0: as long as a run (--seconds)
  int domain = 0;
  std::string ddsperf = "ddsperf";
  int ddsperf_seconds = 10;
  bool keep = false;  // --keep 1: leave the runs' folders and logs (for a look at an abort)
  // --max-feedback-age N: the coordinator's stop rule (clock.max_feedback_age_periods); 0
  // keeps the scenario's (4, the safety setting). A larger one lets a run outlast this VM's
  // stalls so that its overruns are counted over the whole run; late steps are reported.
  int max_age = 0;
  for (std::size_t i = 0; i + 1 < options.rest.size(); i += 2) {
    const std::string& key = options.rest[i];
    const std::string& value = options.rest[i + 1];
    if (key == "--rpsd")
      rpsd = value;
    else if (key == "--coordinator-netns")
      coord_ns = value;
    else if (key == "--node-netns")
      node_ns = value;
    else if (key == "--seconds")
      seconds = std::stod(value);
    else if (key == "--floor-seconds")
      floor_seconds = std::stod(value);
    else if (key == "--domain")
      domain = std::stoi(value);
    else if (key == "--keep")
      keep = value == "1";
    else if (key == "--max-feedback-age")
      max_age = std::stoi(value);
    else if (key == "--ddsperf")
      ddsperf = value;
    else if (key == "--ddsperf-seconds")
      ddsperf_seconds = std::stoi(value);
    else if (key == "--rates")
      rates = bench::parse_rates(value);
    else
      throw std::invalid_argument("unknown option " + key);
  }
  if (options.rest.size() % 2 != 0) throw std::invalid_argument("unknown option " + options.rest.back());
  if (coord_ns.empty() || node_ns.empty()) {
    throw std::invalid_argument(
        "--coordinator-netns and --node-netns are required (bench/realtime-overruns sets them up)");
  }
  if (seconds <= 0.0) throw std::invalid_argument("--seconds: positive");
  if (floor_seconds < 0.0) throw std::invalid_argument("--floor-seconds: positive, or 0 for --seconds");
  if (floor_seconds == 0.0) floor_seconds = seconds;
  if (ddsperf_seconds < 3) throw std::invalid_argument("--ddsperf-seconds: at least 3");
  bench::Fragment fragment("realtime_overruns", argc, argv);
  bench::install_stop_handlers();
  const auto work = std::filesystem::temp_directory_path() / ("rpsd-bench-rt-" + std::to_string(getpid()));
  std::filesystem::create_directories(work);
  const auto src = std::filesystem::absolute(options.source_dir);
  const std::vector<Configuration> tests = configurations(src);
  // Absolute, so that no scenario or node file's folder decides where it is found.
  const std::string lab_lan = (src / "transport/config/lab-lan.xml").string();
  // The lab-LAN profile: eth0, the two hosts' addresses as unicast discovery peers.
  const std::vector<std::string> env{"RPSD_DDS_INTERFACE=eth0", "RPSD_DDS_PEER_1=198.18.0.1",
                                     "RPSD_DDS_PEER_2=198.18.0.2", "RPSD_DDS_PEER_3=198.18.0.2"};
  const std::string load_before = loadavg();
  std::string ddsperf_command;
  std::vector<std::string> did_not_run;  // runs that wrote no summary: the step fails

  for (const int rate : rates) {
    const std::string r = std::to_string(rate);
    // The host's floor at this rate, measured here so that every run below has it beside it.
    std::string refused;
    const realtime::EmptyLoopFloor floor = measure_floor(rate, floor_seconds, refused);
    const std::string floor_id = "realtime_overruns_floor_" + r + "hz";
    const double floor_pct = floor.overruns_percent();
    fragment.add(bench::figure(floor_id,
                               "Empty paced loop before the runs (the host's floor, SCHED_FIFO, CPUs kept awake): "
                               "overruns at " +
                                   r + " Hz",
                               "% of cycles", bench::single(floor_pct)));
    fragment.note(r + " Hz floor: " + std::to_string(floor.overruns) + " overruns of " + std::to_string(floor.cycles) +
                  " cycles, wake-up p99 " + format("%.1f us", floor.wakeup.p99_s * 1e6) + ", max " +
                  format("%.1f us", floor.wakeup.max_s * 1e6) + ", steal " + format("%.3g %%", floor.steal_percent) +
                  (refused.empty() ? "" : "; refused: " + refused));

    // The baseline on the same link with the same configuration: ddsperf pong where the
    // nodes run, ping where the coordinator runs, one ping per control period.
    std::vector<double> perf_p50, perf_p99, perf_max;
    try {
      bench::DdsperfOptions perf;
      perf.program = ddsperf;
      perf.domain = domain;
      perf.seconds = ddsperf_seconds;
      perf.rate = r + "Hz";
      perf.env = env;
      perf.env.push_back("CYCLONEDDS_URI=file://" + lab_lan);
      perf.pong_prefix = {"ip", "netns", "exec", node_ns};
      perf.ping_prefix = {"ip", "netns", "exec", coord_ns};
      // Under the same host conditions as rpsd's run, whose real-time processes keep the
      // CPUs out of slow idle states (clock.keep_cpus_awake, node.keep_cpus_awake).
      const realtime::CpuWakeLatencyHold awake(0);
      if (!awake.held()) fragment.note(r + " Hz: ddsperf ran with the CPUs free to idle: " + awake.refused());
      const bench::DdsperfRun run = bench::run_ddsperf(perf, work);
      for (const auto& l : run.lines) {
        perf_p50.push_back(l.p50_us);
        perf_p99.push_back(l.p99_us);
        perf_max.push_back(l.max_us);
      }
      ddsperf_command = run.command;
    } catch (const bench::Interrupted&) {
      throw;
    } catch (const std::exception& e) {
      fragment.note(r + " Hz: ddsperf on the same link failed: " + std::string(e.what()));
    }
    const std::string perf_id = "realtime_ddsperf_round_trip_" + r + "hz_us";
    for (const Configuration& test : tests) {
      if (!test.rates.empty() && std::find(test.rates.begin(), test.rates.end(), rate) == test.rates.end()) continue;
      const std::string key = test.tag + r;  // names this run's files
      const std::string suffix = test.tag + r + "hz";
      const auto dir = work / (key + "hz");
      std::vector<std::unique_ptr<bench::ChildProcess>> nodes;
      std::vector<std::filesystem::path> node_summaries;
      for (std::size_t i = 0; i < test.nodes.size(); ++i) {
        const std::string n = key + "-node" + std::to_string(i + 1);
        node_summaries.push_back(work / (n + ".json"));
        std::vector<std::string> argv{"ip",
                                      "netns",
                                      "exec",
                                      node_ns,
                                      rpsd,
                                      "servo-node",
                                      (src / test.nodes[i].file).string(),
                                      "--set",
                                      "node.mode=real_time",
                                      "--set",
                                      "node.control_rate_hz=" + r,
                                      "--set",
                                      "dds.config=" + lab_lan,
                                      "--set",
                                      "dds.domain_id=" + std::to_string(domain),
                                      "--summary",
                                      node_summaries.back().string()};
        for (const auto& s : test.nodes[i].sets) argv.insert(argv.end(), {"--set", s});
        nodes.push_back(std::make_unique<bench::ChildProcess>(argv, env, work / (n + ".log")));
      }
      // `seconds` of record from the configuration's start, then free vibration.
      const double left_s = test.record_end_s - test.record_start_s;
      const std::string trim =
          seconds >= left_s ? format("{start_s: %g}", test.record_start_s)
                            : format("{start_s: %g, end_s: %g}", test.record_start_s, test.record_start_s + seconds);
      const std::string load_start = loadavg();
      std::vector<std::string> run_argv{"ip",
                                        "netns",
                                        "exec",
                                        coord_ns,
                                        rpsd,
                                        "run",
                                        (src / test.scenario).string(),
                                        "--out",
                                        dir.string(),
                                        "--set",
                                        "transport.kind=dds",
                                        "--set",
                                        "transport.dds_config=" + lab_lan,
                                        "--set",
                                        "transport.domain_id=" + std::to_string(domain),
                                        "--set",
                                        "clock.mode=real_time",
                                        "--set",
                                        "clock.control_rate_hz=" + r,
                                        "--set",
                                        "ground_motion.trim=" + trim,
                                        "--set",
                                        "ground_motion.pad_after_s=" + format("%g", std::max(0.0, seconds - left_s))};
      for (const auto& s : test.sets) run_argv.insert(run_argv.end(), {"--set", s});
      if (max_age > 0)
        run_argv.insert(run_argv.end(), {"--set", "clock.max_feedback_age_periods=" + std::to_string(max_age)});
      bench::ChildProcess run(run_argv, env, work / (key + "-run.log"));
      // The paced test(s), then the reference and the plots; discovery may take 20 s.
      const int code = run.wait_for(3.0 * seconds + 180.0);
      const std::string load_end = loadavg();
      for (auto& n : nodes) n->stop(SIGTERM, 10.0);
      const std::string run_log = bench::read_text(work / (key + "-run.log"));
      if (code < 0 && run.running()) run.stop(SIGKILL, 5.0);
      std::fprintf(stderr, "realtime_overruns %s at %s Hz: exit %d\n%s", test.name.c_str(), r.c_str(), code,
                   run_log.c_str());
      const std::string title = "Real-time overruns at " + r + " Hz, " + test.name;
      if (!std::filesystem::exists(dir / "summary.json")) {
        // No summary: the test never started (discovery) or the process died. Reported as the
        // figure's outcome, not hidden.
        std::string tail = run_log.substr(run_log.size() > 400 ? run_log.size() - 400 : 0);
        std::replace(tail.begin(), tail.end(), '\n', ' ');
        bench::Figure f = bench::figure("realtime_overruns_" + suffix,
                                        title + ": DID NOT RUN (exit " + std::to_string(code) + ": " + tail + ")",
                                        "% of cycles", bench::Summary{});
        f.aiming_for("runs to completion", false);
        fragment.add(f);
        did_not_run.push_back(test.name + " at " + r + " Hz");
        continue;
      }
      const RunFigures m = read_run(dir);
      const double per_cycle = m.cycles > 0 ? 100.0 / static_cast<double>(m.cycles) : 0.0;
      const double overruns_pct = per_cycle * static_cast<double>(m.overruns);
      const std::string status = m.completed ? "completed" : "DID NOT COMPLETE: " + m.outcome;
      bench::Figure f = bench::figure("realtime_overruns_" + suffix, title + ", coordinator, 2 netns (" + status + ")",
                                      "% of cycles", bench::single(overruns_pct));
      // The target: no more than twice what the empty loop gets from this host. With
      // no overrun of the floor the ratio has no value; the run then meets it only with none.
      if (floor.overruns > 0) {
        const double ratio = overruns_pct / floor_pct;
        f.against(floor_id, "overruns / the empty loop's", ratio);
        f.aiming_for("<= 2x the host's floor", m.completed && ratio <= 2.0);
      } else {
        f.aiming_for("<= 2x the host's floor (0 here)", m.completed && m.overruns == 0);
      }
      fragment.add(f);
      fragment.add(bench::figure("realtime_late_feedback_" + suffix,
                                 "  late feedback (cycles without this step's feedback)", "% of cycles",
                                 bench::single(per_cycle * static_cast<double>(m.late))));
      std::string node_text;
      const double node_overruns = read_nodes(node_summaries, node_text);
      fragment.add(bench::figure("realtime_node_overruns_" + suffix, "  node overruns (the worse node)", "% of cycles",
                                 bench::single(node_overruns)));
      if (!m.p50_us.empty()) {
        bench::Figure rt = bench::figure("realtime_round_trip_" + suffix + "_us", "  round trip p50 (the worse site)",
                                         "us", bench::summarize(m.p50_us));
        if (!perf_p50.empty())
          rt.against(perf_id, "rpsd / ddsperf at the median", rt.value.median / bench::summarize(perf_p50).median);
        fragment.add(rt);
        fragment.add(bench::figure("realtime_round_trip_p99_" + suffix + "_us", "  round trip p99 (the worse site)",
                                   "us", bench::summarize(m.p99_us)));
        fragment.add(bench::figure("realtime_round_trip_max_" + suffix + "_us", "  round trip max (the worse site)",
                                   "us", bench::summarize(m.max_us)));
      }
      fragment.note(r + " Hz, " + test.name + ": " + status + ", " + std::to_string(m.steps) + " of " +
                    std::to_string(m.steps_planned) + " steps; coordinator " + std::to_string(m.overruns) +
                    " overruns, " + std::to_string(m.skipped) + " skipped deadlines, " + std::to_string(m.late) +
                    " late feedback of " + std::to_string(m.cycles) + " cycles, wake-up jitter p99 " +
                    format("%.1f us", 1e6 * m.jitter_p99_s) + ", max " + format("%.1f us", 1e6 * m.jitter_max_s) +
                    (m.sched_fifo ? "" : ", no SCHED_FIFO (" + m.refused + ")") +
                    (m.cpus_awake ? ", CPUs kept awake" : ", CPUs free to idle") + ";" + node_text +
                    " load average at start " + load_start + ", at end " + load_end + ".");
    }
    if (!perf_p50.empty()) {
      fragment.add(bench::figure(
          perf_id, "ddsperf on the same link, ping at " + r + " Hz: round trip p50 (median of per-second values)", "us",
          bench::summarize(perf_p50)));
      fragment.add(bench::figure("realtime_ddsperf_round_trip_p99_" + r + "hz_us", "  the same, p99", "us",
                                 bench::summarize(perf_p99)));
      fragment.add(bench::figure("realtime_ddsperf_round_trip_max_" + r + "hz_us", "  the same, max (largest second)",
                                 "us", bench::summarize(perf_max)));
    }
  }
  if (keep)
    std::fprintf(stderr, "realtime_overruns: kept %s\n", work.c_str());
  else
    std::filesystem::remove_all(work);
  fragment.note(
      "Coordinator (198.18.0.1) and the servo nodes (198.18.0.2) in two network namespaces joined by veth; "
      "transport/config/lab-lan.xml on eth0 with unicast discovery; each scenario in real time over DDS at the rate, " +
      format("%g", seconds) +
      " s of record, then free vibration. Two sites: examples/scenarios/two-site-bridge.yaml (El Centro x 0.1 "
      "untrimmed) against examples/nodes/bridge-pier-site-{1,2}.yaml. One site: the same with "
      "experimental.1.site=1, against bridge-pier-site-1.yaml serving both piers (actuator.channels=2, its "
      "one-channel lists given twice). RTHS (4096 Hz only): "
      "examples/scenarios/rths-benchmark-sample-controller-case-1.yaml from 5 s (after the record's leading zeros), "
      "monte_carlo.runs=2 (its fewest; cycles pooled) against examples/nodes/rths-benchmark-site.yaml (the "
      "benchmark's plant, sample PI controller and converters in the node). Nodes with node.control_rate_hz = the "
      "rate, the limits as the files give them (per second, the same at each rate), "
      "clock.max_feedback_age_periods " +
      (max_age > 0 ? std::to_string(max_age) + " (the default 4 is the hardware safety setting)"
                   : std::string("as the scenario sets it (4)")) +
      ". Overruns are cycles whose work ended past the next deadline, from summary.json (timing.overruns / "
      "timing.cycles) and the nodes' --summary; each against the empty paced loop (realtime/host_floor.h, SCHED_FIFO "
      "80, CPUs kept awake) run " +
      format("%g", floor_seconds) +
      " s just before at the same rate. One run per configuration and rate; load average before " + load_before +
      ", after " + loadavg() +
      " (2 cores shared with other jobs). Before each rate, ddsperf on the same link and configuration (" +
      std::to_string(ddsperf_seconds) +
      " s, pong in the nodes' namespace, ping paced at the rate in the coordinator's, 168 bytes): `" + ddsperf_command +
      "`.");
  // Whether this kernel preempts its own code for the loops (rpsd host-check says the same).
  const realtime::KernelPreemption kernel = realtime::read_kernel_preemption();
  fragment.note("Kernel preemption: " + std::string(realtime::preemption_name(kernel.model)) + " (" + kernel.source +
                (realtime::preempts_for_real_time(kernel.model)
                     ? ")."
                     : "): a real-time thread may wait for other tasks' kernel code at every wake-up of the chain."));
  fragment.write(options.out);
  if (!did_not_run.empty()) {
    std::string text;
    for (const auto& t : did_not_run) text += (text.empty() ? "" : ", ") + t;
    std::fprintf(stderr, "realtime_overruns: no run for %s (see above)\n", text.c_str());
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "realtime_overruns: %s\n", e.what());
  return 1;
}
