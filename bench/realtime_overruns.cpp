// Real-time overruns of the distributed bridge test across two hosts: the coordinator in one
// network namespace, the two servo nodes in another, joined by a veth pair (198.18.0.1 and
// 198.18.0.2), Cyclone's lab-LAN profile (transport/config/lab-lan.xml) on eth0 with unicast
// discovery. bench/realtime-overruns makes the namespaces, runs this, and removes them.
//
// For each control rate: `rpsd servo-node` for both piers (real_time, node.control_rate_hz =
// the rate) and `rpsd run examples/scenarios/two-site-bridge.yaml` in real time at the rate for
// `--seconds` of record (El Centro untrimmed, 40 s, and free vibration after it), both with
// SCHED_FIFO 80 and locked memory as the scenario files ask. Read afterwards: the run's
// summary.json (timing.cycles, overruns, late_feedback, round trip per site, outcome) and
// each node's --summary (cycles, overruns, missed periods, holds).
#include <unistd.h>

#include <algorithm>
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
#include "ddsperf.h"
#include "rpsd/realtime/cpu_wake_latency.h"

namespace {

using namespace rpsd;
using nlohmann::json;

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

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 1);
  std::string rpsd = RPSD_BENCH_RPSD, coord_ns, node_ns;
  std::vector<int> rates{1024, 2048, 4096};
  double seconds = 60.0;
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
  if (ddsperf_seconds < 3) throw std::invalid_argument("--ddsperf-seconds: at least 3");
  bench::Fragment fragment("realtime_overruns", argc, argv);
  bench::install_stop_handlers();
  const auto work = std::filesystem::temp_directory_path() / ("rpsd-bench-rt-" + std::to_string(getpid()));
  std::filesystem::create_directories(work);
  const auto src = std::filesystem::absolute(options.source_dir);
  // Absolute, so that no scenario or node file's folder decides where it is found.
  const std::string lab_lan = (src / "transport/config/lab-lan.xml").string();
  // The lab-LAN profile: eth0, the two hosts' addresses as unicast discovery peers.
  const std::vector<std::string> env{"RPSD_DDS_INTERFACE=eth0", "RPSD_DDS_PEER_1=198.18.0.1",
                                     "RPSD_DDS_PEER_2=198.18.0.2", "RPSD_DDS_PEER_3=198.18.0.2"};
  // El Centro is 40 s long: the whole record, then free vibration up to `seconds`.
  constexpr double kRecordSeconds = 40.0;
  const std::string trim =
      seconds >= kRecordSeconds ? "{start_s: 0}" : "{start_s: 0, end_s: " + format("%g", seconds) + "}";
  const std::string pad = format("%g", std::max(0.0, seconds - kRecordSeconds));
  const std::string load_before = loadavg();
  std::string ddsperf_command;
  std::vector<std::string> did_not_run;  // rates whose run wrote no summary: the step fails

  for (const int rate : rates) {
    const std::string r = std::to_string(rate);
    const auto dir = work / (r + "hz");
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
    std::vector<std::unique_ptr<bench::ChildProcess>> nodes;
    for (int site = 1; site <= 2; ++site) {
      nodes.push_back(std::make_unique<bench::ChildProcess>(
          std::vector<std::string>{
              "ip", "netns", "exec", node_ns, rpsd, "servo-node",
              (src / ("examples/nodes/bridge-pier-site-" + std::to_string(site) + ".yaml")).string(), "--set",
              "node.mode=real_time", "--set", "node.control_rate_hz=" + r, "--set", "dds.config=" + lab_lan, "--set",
              "dds.domain_id=" + std::to_string(domain), "--summary",
              (work / (r + "-node" + std::to_string(site) + ".json")).string()},
          env, work / (r + "-node" + std::to_string(site) + ".log")));
    }
    const std::string load_start = loadavg();
    std::vector<std::string> run_argv{"ip",
                                      "netns",
                                      "exec",
                                      coord_ns,
                                      rpsd,
                                      "run",
                                      (src / "examples/scenarios/two-site-bridge.yaml").string(),
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
                                      "ground_motion.pad_after_s=" + pad};
    if (max_age > 0)
      run_argv.insert(run_argv.end(), {"--set", "clock.max_feedback_age_periods=" + std::to_string(max_age)});
    bench::ChildProcess run(run_argv, env, work / (r + "-run.log"));
    // The paced test, then the reference and the plots; discovery may take 20 s.
    const int code = run.wait_for(3.0 * seconds + 180.0);
    const std::string load_end = loadavg();
    for (auto& n : nodes) n->stop(SIGTERM, 10.0);
    const std::string run_log = bench::read_text(work / (r + "-run.log"));
    if (code < 0 && run.running()) run.stop(SIGKILL, 5.0);
    std::fprintf(stderr, "realtime_overruns %s Hz: exit %d\n%s", r.c_str(), code, run_log.c_str());
    if (!std::filesystem::exists(dir / "summary.json")) {
      // No summary: the test never started (discovery) or the process died. Reported as the
      // figure's outcome, not hidden.
      std::string tail = run_log.substr(run_log.size() > 400 ? run_log.size() - 400 : 0);
      std::replace(tail.begin(), tail.end(), '\n', ' ');
      bench::Figure f = bench::figure(
          "realtime_overruns_" + r + "hz",
          "Real-time overruns at " + r + " Hz: DID NOT RUN (exit " + std::to_string(code) + ": " + tail + ")",
          "% of cycles", bench::Summary{});
      f.aiming_for(rate == 4096 ? "< 0.1 %" : "runs to completion", false);
      fragment.add(f);
      did_not_run.push_back(r + " Hz");
      continue;
    }
    const json s = read_json(dir / "summary.json");
    const json& t = s["timing"];
    const auto cycles = t.value("cycles", std::int64_t{0});
    const double per_cycle = cycles > 0 ? 100.0 / static_cast<double>(cycles) : 0.0;
    const double overruns_pct = per_cycle * static_cast<double>(t.value("overruns", std::int64_t{0}));
    const double late_pct = per_cycle * static_cast<double>(t.value("late_feedback", std::int64_t{0}));
    const bool completed = s.value("completed", false);
    const std::string outcome = s.value("outcome", std::string("?"));
    std::string status = completed ? "completed" : "DID NOT COMPLETE: " + outcome;

    bench::Figure f = bench::figure("realtime_overruns_" + r + "hz",
                                    "Real-time overruns at " + r + " Hz, coordinator, 2 netns (" + status + ")",
                                    "% of cycles", bench::single(overruns_pct));
    if (rate == 4096)
      f.aiming_for("< 0.1 %", completed && overruns_pct < 0.1);
    else if (!completed)
      f.aiming_for("runs to completion", false);
    fragment.add(f);
    fragment.add(bench::figure("realtime_late_feedback_" + r + "hz",
                               "  late feedback (cycles without this step's feedback)", "% of cycles",
                               bench::single(late_pct)));

    double node_overruns = 0.0, node_missed = 0.0;
    std::string node_text;
    for (int site = 1; site <= 2; ++site) {
      const auto file = work / (r + "-node" + std::to_string(site) + ".json");
      if (!std::filesystem::exists(file)) {
        node_text += " node " + std::to_string(site) + ": no summary;";
        continue;
      }
      const json n = read_json(file);
      const auto ncycles = n.value("cycles", std::int64_t{0});
      const double pct =
          ncycles > 0 ? 100.0 * static_cast<double>(n.value("overruns", std::int64_t{0})) / static_cast<double>(ncycles)
                      : 0.0;
      node_overruns = std::max(node_overruns, pct);
      node_missed = std::max(node_missed, static_cast<double>(n.value("missed_periods", std::int64_t{0})));
      node_text += " node " + std::to_string(site) + ": " + std::to_string(n.value("overruns", std::int64_t{0})) +
                   " overruns of " + std::to_string(ncycles) + " cycles, " +
                   std::to_string(n.value("missed_periods", std::int64_t{0})) + " missed periods, " +
                   std::to_string(n.value("holds", std::int64_t{0})) + " holds, jitter p99 " +
                   format("%.1f us", 1e6 * n["jitter"].value("p99_s", 0.0)) +
                   (n.value("faulted", false) ? ", FAULTED" : "") +
                   (n.value("sched_fifo", false) ? "" : ", no SCHED_FIFO") +
                   (n.value("cpus_kept_awake", false) ? "" : ", CPUs free to idle") + ";";
    }
    fragment.add(bench::figure("realtime_node_overruns_" + r + "hz", "  node overruns (the worse of the two nodes)",
                               "% of cycles", bench::single(node_overruns)));

    std::vector<double> p50, p99, max;
    for (const auto& site : t["sites"]) {
      p50.push_back(1e6 * site["round_trip"].value("p50_s", 0.0));
      p99.push_back(1e6 * site["round_trip"].value("p99_s", 0.0));
      max.push_back(1e6 * site["round_trip"].value("max_s", 0.0));
    }
    if (!p50.empty()) {
      bench::Figure rt = bench::figure("realtime_round_trip_" + r + "hz_us", "  round trip p50 (the worse site)", "us",
                                       bench::single(*std::max_element(p50.begin(), p50.end())));
      if (!perf_p50.empty()) {
        rt.against("realtime_ddsperf_round_trip_" + r + "hz_us", "rpsd / ddsperf at the median",
                   rt.value.median / bench::summarize(perf_p50).median);
      }
      fragment.add(rt);
      fragment.add(bench::figure("realtime_round_trip_p99_" + r + "hz_us", "  round trip p99 (the worse site)", "us",
                                 bench::single(*std::max_element(p99.begin(), p99.end()))));
      fragment.add(bench::figure("realtime_round_trip_max_" + r + "hz_us", "  round trip max (the worse site)", "us",
                                 bench::single(*std::max_element(max.begin(), max.end()))));
    }
    if (!perf_p50.empty()) {
      fragment.add(bench::figure("realtime_ddsperf_round_trip_" + r + "hz_us",
                                 "  ddsperf on the same link, ping at " + r + " Hz, p50 (median of per-second values)",
                                 "us", bench::summarize(perf_p50)));
      fragment.add(bench::figure("realtime_ddsperf_round_trip_p99_" + r + "hz_us", "  the same, p99", "us",
                                 bench::summarize(perf_p99)));
      fragment.add(bench::figure("realtime_ddsperf_round_trip_max_" + r + "hz_us", "  the same, max (largest second)",
                                 "us", bench::summarize(perf_max)));
    }
    fragment.note(r + " Hz: " + status + ", " + std::to_string(s.value("steps", 0)) + " of " +
                  std::to_string(s.value("steps_planned", 0)) + " steps; coordinator " +
                  std::to_string(t.value("overruns", 0)) + " overruns, " +
                  std::to_string(t.value("skipped_deadlines", 0)) + " skipped deadlines, " +
                  std::to_string(t.value("late_feedback", 0)) + " late feedback of " + std::to_string(cycles) +
                  " cycles, wake-up jitter p99 " + format("%.1f us", 1e6 * t["jitter"].value("p99_s", 0.0)) + ", max " +
                  format("%.1f us", 1e6 * t["jitter"].value("max_s", 0.0)) +
                  (t.value("sched_fifo", false) ? "" : ", no SCHED_FIFO (" + t.value("refused", std::string()) + ")") +
                  (t.value("cpus_kept_awake", false) ? ", CPUs kept awake" : ", CPUs free to idle") + ";" + node_text +
                  " load average at start " + load_start + ", at end " + load_end + ".");
  }
  if (keep)
    std::fprintf(stderr, "realtime_overruns: kept %s\n", work.c_str());
  else
    std::filesystem::remove_all(work);
  fragment.note(
      "Coordinator (198.18.0.1) and both servo nodes (198.18.0.2) in two network namespaces joined by veth; "
      "transport/config/lab-lan.xml on eth0 with unicast discovery; examples/scenarios/two-site-bridge.yaml in real "
      "time over DDS at the rate, " +
      format("%g", seconds) +
      " s of record (El Centro x 0.1 untrimmed, then free "
      "vibration); nodes examples/nodes/bridge-pier-site-{1,2}.yaml with node.control_rate_hz = the rate "
      "(their servo model at its own 8192 Hz), the limits as the files give them (per second, the same at each "
      "rate), clock.max_feedback_age_periods " +
      (max_age > 0 ? std::to_string(max_age) + " (the default 4 is the hardware safety setting)"
                   : std::string("as the scenario sets it (4)")) +
      ". Overruns are cycles whose work ended past the next deadline, "
      "from summary.json (timing.overruns / timing.cycles) and the nodes' --summary. One run per rate; "
      "load average before " +
      load_before + ", after " + loadavg() +
      " (2 cores shared with other jobs). Before each rate, "
      "ddsperf on the same link and configuration (" +
      std::to_string(ddsperf_seconds) +
      " s, pong in the nodes' "
      "namespace, ping paced at the rate in the coordinator's, 168 bytes): `" +
      ddsperf_command + "`.");
  fragment.write(options.out);
  if (!did_not_run.empty()) {
    std::string rates_text;
    for (const auto& r : did_not_run) rates_text += (rates_text.empty() ? "" : ", ") + r;
    std::fprintf(stderr, "realtime_overruns: no run at %s (see above)\n", rates_text.c_str());
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "realtime_overruns: %s\n", e.what());
  return 1;
}
