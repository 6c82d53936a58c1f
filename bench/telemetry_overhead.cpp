// The loop's cost with a monitor attached: the paper's SDOF RPsD as fast as possible (as
// `rpsd run examples/scenarios/elcentro-sdof.yaml` builds it), once with the telemetry
// published on loopback and a subscriber reading it as `rpsd monitor` does, once with none,
// trials interleaved in one run; reported as the ratio of the two speeds. As fast as possible
// the loop waits for the recorder's writer thread when its queue is full, so the ratio is
// also what the publisher costs the writer; in real time the loop never waits for it
// (docs/telemetry.md). The default rate (256 samples/s of test time) and every step (1024/s).
#include <unistd.h>
#include <atomic>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>

#include "bench_report.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/telemetry/telemetry_publisher.h"
#include "rpsd/telemetry/telemetry_subscriber.h"

namespace {

using namespace rpsd;

// One run of the test, with `publisher` on its recorder (or none). Not inlined, as
// sdof_throughput's trials.
[[gnu::noinline]] void loop_trial(const hybrid_test::TestConfig& scenario, telemetry::TelemetryPublisher* publisher) {
  std::vector<coordinator::RecordObserver*> observers;
  if (publisher) observers.push_back(publisher);
  hybrid_test::TestAssembly test(scenario, {{}, false, false, {}, nullptr, observers});
  if (publisher) {
    telemetry::TelemetryRunInfo info;
    info.run_id = test.run_id();
    info.steps_planned = test.steps_planned();
    info.control_rate_hz = scenario.control_rate_hz;
    info.channels = static_cast<int>(scenario.experimental.size());
    info.live = &test.live_counters();
    publisher->start(info);
  }
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
  for (std::int64_t n = 0; n < test.steps_planned() && outcome == coordinator::StepOutcome::kOk; ++n)
    outcome = test.step();
  const hybrid_test::TestRun done = test.finish(outcome);
  if (done.steps != test.steps_planned()) throw std::runtime_error("a trial stopped early");
  if (publisher) publisher->end({"completed", false, 0, 0});
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 15);
  bench::Fragment fragment("telemetry_overhead", argc, argv);
  const auto file = scenarios::load_study(options.source_dir / "examples/scenarios/elcentro-sdof.yaml");
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const double simulated_s = scenario.duration_s;

  const auto domain = static_cast<std::uint32_t>(190 + ::getpid() % 40);
  const std::string xml = (options.source_dir / "transport/config/loopback.xml").string();
  telemetry::TelemetrySubscriber subscriber({domain, xml, 77});
  telemetry::TelemetryPublisher decimated({domain, xml, 77, "bench", 256.0});
  telemetry::TelemetryPublisher every_step({domain, xml, 77, "bench", scenario.control_rate_hz});
  std::atomic<bool> done{false};
  std::size_t batches_read = 0;
  std::thread reader([&] {
    std::vector<telemetry::TelemetryBatch> batches;
    std::vector<telemetry::TelemetryEvent> events;
    while (!done.load()) {
      subscriber.wait(std::chrono::milliseconds(20));
      subscriber.take(batches, events);
      batches_read += batches.size();
      batches.clear();
      events.clear();
    }
  });

  // None, decimated, every step, ... after one untimed trial of each: the three trials of a
  // round see the same machine, and each round gives one ratio.
  const auto run_none = [&] { loop_trial(scenario, nullptr); };
  const auto run_decimated = [&] { loop_trial(scenario, &decimated); };
  const auto run_every = [&] { loop_trial(scenario, &every_step); };
  run_none();
  run_decimated();
  run_every();
  bench::Trials none_s, decimated_s, every_s;
  std::vector<double> decimated_ratios, every_ratios;  // speed with / speed without = time without / time with
  const auto time_one = [](bench::Trials& trials, const std::function<void()>& body) {
    const bench::Trials one = bench::time_trials(1, 0, body);
    trials.wall_s.push_back(one.wall_s[0]);
    trials.cpu_s.push_back(one.cpu_s[0]);
  };
  for (int i = 0; i < options.repetitions; ++i) {
    time_one(none_s, run_none);
    time_one(decimated_s, run_decimated);
    time_one(every_s, run_every);
    decimated_ratios.push_back(none_s.wall_s.back() / decimated_s.wall_s.back());
    every_ratios.push_back(none_s.wall_s.back() / every_s.wall_s.back());
  }
  done.store(true);
  reader.join();
  if (batches_read == 0) throw std::runtime_error("the subscriber read nothing");

  const auto x_realtime = [&](const std::vector<double>& seconds) {
    return bench::map_summary(bench::summarize(seconds), [&](double s) { return simulated_s / s; });
  };
  fragment.add(bench::figure("telemetry_none_x_realtime", "Paper SDOF as fast as possible, no telemetry (baseline)",
                             "x real time", x_realtime(none_s.wall_s), x_realtime(none_s.cpu_s)));
  bench::Figure with;
  with = bench::figure("telemetry_monitored_x_realtime",
                       "  the same, telemetry published (256 samples/s) and read by a subscriber", "x real time",
                       x_realtime(decimated_s.wall_s), x_realtime(decimated_s.cpu_s));
  with.against("telemetry_none_x_realtime", "with telemetry / without (speed), median of the rounds' ratios",
               bench::summarize(decimated_ratios).median);
  fragment.add(with);
  bench::Figure ratio =
      bench::figure("telemetry_monitored_ratio", "  the same: speed with telemetry over without, round by round",
                    "with / without", bench::summarize(decimated_ratios));
  ratio.aiming_for(">= 0.9", ratio.value.median >= 0.9);
  fragment.add(ratio);
  bench::Figure every =
      bench::figure("telemetry_every_step_ratio", "  the same with every step published (1024 samples/s), over without",
                    "with / without", bench::summarize(every_ratios));
  fragment.add(every);
  char text[400];
  std::snprintf(text, sizeof text,
                "El Centro SDOF, %.0f s of record at %.0f Hz, as fast as possible in process; the publisher and a "
                "subscriber on loopback (transport/config/loopback.xml, domain %u) in this process, the subscriber "
                "taking every 20 ms on its own thread; %d rounds of none / 256 per s / every step.",
                simulated_s, scenario.control_rate_hz, domain, options.repetitions);
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "telemetry_overhead: %s\n", e.what());
  return 1;
}
