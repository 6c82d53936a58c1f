// The DDS link on loopback, in one step so that rpsd and ddsperf meet the same machine load
// and the same Cyclone configuration (transport/config/loopback.xml, a private domain).
//
// (1) The paper SDOF (examples/scenarios/elcentro-sdof.yaml, El Centro + 20 s of free vibration,
//     61,429 steps at 1024 Hz) lock-step over DDS: the coordinator built as `rpsd run` builds
//     it (hybrid_test::TestAssembly with transport.kind=dds, test 7) in this process, the
//     specimen on a separate `rpsd servo-node` process (examples/nodes/bridge-pier-site-1.yaml:
//     the same 700.8 kN/m springs on the same MTS 244 servo model, lock_step). Timed: the
//     steps, from after discovery (building the assembly) to the last feedback; not the
//     reference run, the criteria or the plots that `rpsd run` adds. Multiple of real time,
//     against the same test in process measured in the same run.
//     Command-to-feedback round trip of those runs (summary.json's timing.sites[].round_trip,
//     the same histogram): p50 and p99. Each repetition runs it twice: as configured by
//     default, and with transport.busy_wait_s = 0.001 (the coordinator polls for its
//     feedback for up to 1 ms before sleeping on the waitset).
// (2) ddsperf between two processes (`ddsperf pong waitset`, `ddsperf ping size 168 waitset`):
//     closed-loop pings, a new one as soon as the pong is in, the traffic pattern of lock-step
//     (rpsd sends the next command when the feedback is in and the step integrated); 168
//     bytes, about the feedback sample's size (the command's is about 96). Then pings paced at 1024 Hz.
//     ddsperf prints the round trip's percentiles once a second, each as half the round trip
//     (support/ddsperf.h); a figure is twice that, the median over those lines (the first, with
//     discovery, left out). rpsd's payloads: command 112 bytes of CDR, feedback 176; ddsperf's
//     168 both ways.
// --dds-config FILE runs all of it on another Cyclone configuration (docs/dds-transport.md:
// the shared-memory one).
// The two alternate repetition by repetition, so both see the same load.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_report.h"
#include "child_process.h"
#include "ddsperf.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/realtime/cpu_wake_latency.h"
#include "rpsd/scenarios/study_file.h"

namespace {

using namespace rpsd;

struct LockStepRun {
  double discovery_s = 0.0, wall_s = 0.0, cpu_s = 0.0;
  realtime::LatencySummary round_trip;
  std::int64_t steps = 0;
};

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 5);
  std::string rpsd = RPSD_BENCH_RPSD, ddsperf = "ddsperf";
  // Above the system tests' domains (1-200); ddsperf matches any ddsperf in its domain.
  int domain = 201 + static_cast<int>(getpid() % 32);
  int ddsperf_seconds = 10;
  // The Cyclone configuration of both rpsd processes and of ddsperf (e.g. a shared-memory one).
  std::filesystem::path dds_config = "transport/config/loopback.xml";
  for (std::size_t i = 0; i + 1 < options.rest.size(); i += 2) {
    if (options.rest[i] == "--rpsd")
      rpsd = options.rest[i + 1];
    else if (options.rest[i] == "--ddsperf")
      ddsperf = options.rest[i + 1];
    else if (options.rest[i] == "--domain")
      domain = std::stoi(options.rest[i + 1]);
    else if (options.rest[i] == "--ddsperf-seconds")
      ddsperf_seconds = std::stoi(options.rest[i + 1]);
    else if (options.rest[i] == "--dds-config")
      dds_config = options.rest[i + 1];
    else
      throw std::invalid_argument("unknown option " + options.rest[i]);
  }
  if (options.rest.size() % 2 != 0) throw std::invalid_argument("unknown option " + options.rest.back());
  // ddsperf prints once a second and the first line (discovery) is left out.
  if (ddsperf_seconds < 3) throw std::invalid_argument("--ddsperf-seconds: at least 3");
  bench::Fragment fragment("dds_link", argc, argv);
  bench::install_stop_handlers();
  const auto work = std::filesystem::temp_directory_path() / ("rpsd-bench-dds-" + std::to_string(getpid()));
  std::filesystem::create_directories(work);
  const auto config =
      std::filesystem::absolute(dds_config.is_absolute() ? dds_config : options.source_dir / dds_config);
  if (!std::filesystem::exists(config)) throw std::invalid_argument("--dds-config: no file " + config.string());
  const std::vector<std::string> env{"CYCLONEDDS_URI=file://" + config.string()};
  const auto node_yaml = (options.source_dir / "examples/nodes/bridge-pier-site-1.yaml").string();

  const auto sdof = [&](const std::string& transport, const std::string& more = {}) {
    return scenarios::load_study(
        options.source_dir / "examples/scenarios/elcentro-sdof.yaml",
        {scenarios::parse_override("ground_motion.pad_after_s=20"),
         scenarios::parse_override("transport={kind: " + transport +
                                   ", test_id: 7, domain_id: " + std::to_string(domain) +
                                   ", dds_config: " + config.string() + ", discovery_timeout_s: 20" + more + "}")});
  };
  const auto dds_file = sdof("dds");
  // The same with the coordinator polling for its feedback for up to 1 ms before sleeping.
  const auto busy_file = sdof("dds", ", busy_wait_s: 0.001");
  const auto local_file = sdof("in_process");
  const auto& dds_scenario = std::get<hybrid_test::TestConfig>(dds_file.study);
  const auto& busy_scenario = std::get<hybrid_test::TestConfig>(busy_file.study);
  const auto& local_scenario = std::get<hybrid_test::TestConfig>(local_file.study);
  const double simulated_s = dds_scenario.duration_s;

  // One lock-step run against a fresh node (its step count starts with the test's).
  const auto lock_step = [&](const hybrid_test::TestConfig& scenario) {
    bench::ChildProcess node({rpsd, "servo-node", node_yaml, "--set", "node.mode=lock_step", "--set",
                              "dds.domain_id=" + std::to_string(domain), "--set", "dds.config=" + config.string()},
                             {}, work / "node.log");
    LockStepRun r;
    const auto start = bench::Clock::now();
    hybrid_test::TestAssembly test(scenario, {});
    r.discovery_s = bench::seconds_since(start);
    const double cpu_start = bench::thread_cpu_s();
    const auto loop_start = bench::Clock::now();
    coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
    for (std::int64_t n = 0; n < test.steps_planned() && outcome == coordinator::StepOutcome::kOk; ++n)
      outcome = test.step();
    r.wall_s = bench::seconds_since(loop_start);
    r.cpu_s = bench::thread_cpu_s() - cpu_start;
    const hybrid_test::TestRun done = test.finish(outcome);
    node.stop(SIGTERM, 10.0);
    if (done.steps != done.steps_planned || done.timing.sites.size() != 1) {
      throw std::runtime_error("the lock-step run stopped at step " + std::to_string(done.steps) + " of " +
                               std::to_string(done.steps_planned) + "; node log:\n" +
                               bench::read_text(work / "node.log"));
    }
    r.round_trip = done.timing.sites[0].round_trip;
    r.steps = done.steps;
    return r;
  };

  // Baseline: the same test in process, as sdof_throughput times it.
  const auto local = bench::time_trials(options.repetitions, 1, [&] {
    hybrid_test::TestAssembly test(local_scenario, {});
    coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
    for (std::int64_t n = 0; n < test.steps_planned() && outcome == coordinator::StepOutcome::kOk; ++n)
      outcome = test.step();
    if (test.finish(outcome).steps != test.steps_planned())
      throw std::runtime_error("the in-process run stopped early");
  });

  std::vector<LockStepRun> runs, busy_runs;
  std::vector<double> perf_p50, perf_p99, paced_p50, paced_p99, perf_busy_s;
  // ddsperf's p50 and p99 of each repetition (the median over its lines), to pair with rpsd's runs.
  std::vector<double> rep_perf_p50, rep_perf_p99;
  std::string perf_command, paced_command;
  for (int i = 0; i < options.repetitions; ++i) {
    runs.push_back(lock_step(dds_scenario));
    busy_runs.push_back(lock_step(busy_scenario));
    bench::DdsperfOptions perf;
    perf.program = ddsperf;
    perf.domain = domain;
    perf.seconds = ddsperf_seconds;
    perf.env = env;
    // Under the same host conditions as rpsd's runs: the lock-step node keeps the CPUs out
    // of slow idle states while it runs (node.keep_cpus_awake), so ddsperf gets the same.
    const realtime::CpuWakeLatencyHold awake(0);
    if (!awake.held()) fragment.note("ddsperf ran with the CPUs free to idle: " + awake.refused());
    const bench::DdsperfRun closed = bench::run_ddsperf(perf, work);
    std::vector<double> rep50, rep99;
    for (const auto& l : closed.lines) {
      rep50.push_back(l.p50_us);
      rep99.push_back(l.p99_us);
      perf_busy_s.push_back(bench::closed_loop_busy_s(l));
    }
    perf_p50.insert(perf_p50.end(), rep50.begin(), rep50.end());
    perf_p99.insert(perf_p99.end(), rep99.begin(), rep99.end());
    rep_perf_p50.push_back(bench::summarize(rep50).median);
    rep_perf_p99.push_back(bench::summarize(rep99).median);
    perf.rate = "1024Hz";
    const bench::DdsperfRun paced = bench::run_ddsperf(perf, work);
    for (const auto& l : paced.lines) {
      paced_p50.push_back(l.p50_us);
      paced_p99.push_back(l.p99_us);
    }
    perf_command = closed.command;
    paced_command = paced.command;
  }
  std::filesystem::remove_all(work);

  // Per run: loop wall and CPU time, discovery, round-trip p50/p99/max (us).
  struct Series {
    std::vector<double> wall, cpu, discovery, rt_p50, rt_p99, rt_max;
  };
  const auto series = [](const std::vector<LockStepRun>& of) {
    Series s;
    for (const auto& r : of) {
      s.wall.push_back(r.wall_s);
      s.cpu.push_back(r.cpu_s);
      s.discovery.push_back(r.discovery_s);
      s.rt_p50.push_back(1e6 * r.round_trip.p50_s);
      s.rt_p99.push_back(1e6 * r.round_trip.p99_s);
      s.rt_max.push_back(1e6 * r.round_trip.max_s);
    }
    return s;
  };
  const Series plain = series(runs), busy = series(busy_runs);
  const auto& [wall, cpu, discovery, rt_p50, rt_p99, rt_max] = plain;
  const auto x_realtime = [&](double s) { return simulated_s / s; };
  const bench::Summary dds_x = bench::map_summary(bench::summarize(wall), x_realtime);
  const bench::Summary busy_x = bench::map_summary(bench::summarize(busy.wall), x_realtime);
  const bench::Summary local_x = bench::map_summary(bench::summarize(local.wall_s), x_realtime);

  fragment.add(bench::figure("sdof_dds_lockstep_x_realtime",
                             "Paper SDOF RPsD lock-step through the DDS link (loopback, node process), 60 s of record",
                             "x real time", dds_x, bench::map_summary(bench::summarize(cpu), x_realtime))
                   .against("sdof_inprocess_x_realtime_same_run", "DDS / in process", dds_x.median / local_x.median)
                   .aiming_for(">= 20", dds_x.median >= 20.0));
  fragment.add(bench::figure("sdof_dds_lockstep_busy_wait_x_realtime", "  the same with transport.busy_wait_s = 0.001",
                             "x real time", busy_x, bench::map_summary(bench::summarize(busy.cpu), x_realtime))
                   .against("sdof_inprocess_x_realtime_same_run", "DDS / in process", busy_x.median / local_x.median)
                   .aiming_for(">= 20", busy_x.median >= 20.0));
  fragment.add(bench::figure("sdof_inprocess_x_realtime_same_run", "  baseline: the same test in process, same run",
                             "x real time", local_x, bench::map_summary(bench::summarize(local.cpu_s), x_realtime)));
  fragment.add(bench::figure("sdof_dds_discovery_s", "  discovery before the first step (not in the figure above)", "s",
                             bench::summarize(discovery)));

  const bench::Summary perf50 = bench::summarize(perf_p50);
  const bench::Summary perf99 = bench::summarize(perf_p99);
  // The load on this shared machine swings between repetitions more than the link differs:
  // each rpsd run is divided by the ddsperf run that follows it, and the ratio is the median
  // of those per-repetition ratios (their spread is the ratio figures' min and max).
  const auto per_pair = [&](const std::vector<double>& rpsd_us, const std::vector<double>& ddsperf_us) {
    std::vector<double> ratios;
    for (std::size_t i = 0; i < rpsd_us.size() && i < ddsperf_us.size(); ++i)
      ratios.push_back(rpsd_us[i] / ddsperf_us[i]);
    return bench::summarize(ratios);
  };
  const bench::Summary ratio50 = per_pair(rt_p50, rep_perf_p50), ratio99 = per_pair(rt_p99, rep_perf_p99);
  const bench::Summary busy_ratio50 = per_pair(busy.rt_p50, rep_perf_p50);
  const bench::Summary busy_ratio99 = per_pair(busy.rt_p99, rep_perf_p99);
  const char* const pair_label = "rpsd / ddsperf, median of the per-repetition ratios";
  fragment.add(bench::figure("dds_round_trip_us", "DDS round trip, rpsd lock-step command to feedback, median (p50)",
                             "us", bench::summarize(rt_p50))
                   .against("ddsperf_round_trip_us", pair_label, ratio50.median)
                   .aiming_for("<= 1.2 x ddsperf at the median", ratio50.median <= 1.2));
  fragment.add(bench::figure("dds_round_trip_p99_us", "  the same, p99", "us", bench::summarize(rt_p99))
                   .against("ddsperf_round_trip_p99_us", pair_label, ratio99.median));
  fragment.add(bench::figure("dds_round_trip_max_us", "  the same, max", "us", bench::summarize(rt_max)));
  fragment.add(bench::figure("dds_round_trip_p50_ratio", "  p50 over ddsperf's, per repetition", "x ddsperf", ratio50));
  fragment.add(bench::figure("dds_round_trip_p99_ratio", "  p99 over ddsperf's, per repetition", "x ddsperf", ratio99));
  fragment.add(bench::figure("dds_round_trip_busy_wait_us",
                             "DDS round trip, rpsd lock-step with transport.busy_wait_s = 0.001, p50", "us",
                             bench::summarize(busy.rt_p50))
                   .against("ddsperf_round_trip_us", pair_label, busy_ratio50.median)
                   .aiming_for("<= 1.2 x ddsperf at the median", busy_ratio50.median <= 1.2));
  fragment.add(bench::figure("dds_round_trip_busy_wait_p99_us", "  the same, p99", "us", bench::summarize(busy.rt_p99))
                   .against("ddsperf_round_trip_p99_us", pair_label, busy_ratio99.median));
  fragment.add(bench::figure("dds_round_trip_busy_wait_p50_ratio", "  p50 over ddsperf's, per repetition", "x ddsperf",
                             busy_ratio50));
  fragment.add(bench::figure("ddsperf_round_trip_us",
                             "DDS round trip, ddsperf closed-loop ping/pong, same config, median (p50)", "us", perf50));
  fragment.add(bench::figure("ddsperf_round_trip_p99_us", "  the same, p99", "us", perf99));
  // Closed loop, the round trips of one second fill it: ~1 s shows ddsperf's printed halves read
  // as whole round trips (0.5 would be the halves themselves).
  fragment.add(bench::figure("ddsperf_round_trip_s_per_s",
                             "  check: count x mean round trip of each ddsperf second (closed loop: about 1)", "s",
                             bench::summarize(perf_busy_s)));
  fragment.add(bench::figure("ddsperf_1024hz_round_trip_us",
                             "DDS round trip, ddsperf ping paced at 1024 Hz, median (p50)", "us",
                             bench::summarize(paced_p50)));
  fragment.add(bench::figure("ddsperf_1024hz_round_trip_p99_us", "  the same, p99", "us", bench::summarize(paced_p99)));

  char text[2400];
  std::snprintf(
      text, sizeof text,
      "rpsd: %lld lock-step steps per run, %d runs of each variant (default; transport.busy_wait_s = 0.001), "
      "alternating, each against a fresh `%s servo-node %s --set node.mode=lock_step` "
      "(domain %d, %s); the coordinator is this process (hybrid_test::TestAssembly, "
      "as `rpsd run` builds it). The rpsd round trip is the coordinator's command-to-feedback time and includes "
      "the node's plant step (the servo model over one period, RK4 at 8192 Hz: 8 substeps, about 0.7 us) and "
      "both sides' copies; its histogram has 1 us bins (upper edges). Each rpsd figure is the median over runs "
      "of that run's p50/p99/max; throughput is simulated seconds (%.2f) over the loop's wall time, discovery "
      "excluded. ddsperf: `%s`, CYCLONEDDS_URI=file://%s, %d s a run; a sample is "
      "one per-second line (the first left out), twice the figures it prints (ddsperf prints half the round trip). "
      "Paced: `%s`.",
      static_cast<long long>(runs.front().steps), options.repetitions, rpsd.c_str(), node_yaml.c_str(), domain,
      config.string().c_str(), simulated_s, perf_command.c_str(), config.string().c_str(), ddsperf_seconds,
      paced_command.c_str());
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "dds_link: %s\n", e.what());
  return 1;
}
