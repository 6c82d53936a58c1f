// The floor under the real-time overrun figures: what this machine does to a paced loop that
// does nothing. One thread, SCHED_FIFO 80 and locked memory as rpsd's loops ask, sleeps to
// absolute deadlines (realtime::Pacer, as the coordinator and the node pace) at each control
// rate for --seconds, with no work, no DDS and no other process of rpsd running; once with the
// CPUs free to idle and once kept awake (cpu_wake_latency.h, as rpsd's real-time loops do by
// default). An overrun here is a wake-up later than the next deadline: time the host did not
// give the thread. No loop with work in it can overrun less often on the same host, so this
// bounds what the 4096 Hz target of realtime_overruns can reach here. The host's steal time
// over the run (from /proc/stat) is reported beside it: on a VM the hypervisor's share.
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_report.h"
#include "rpsd/realtime/cpu_wake_latency.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/realtime/realtime_setup.h"

namespace {

using namespace rpsd;

// Jiffies of all CPUs together: everything, and the part stolen by the hypervisor.
struct CpuTimes {
  long long total = 0, steal = 0;
};

CpuTimes read_cpu_times() {
  std::ifstream in("/proc/stat");
  std::string label;
  in >> label;
  if (label != "cpu") throw std::runtime_error("/proc/stat: no cpu line");
  CpuTimes t;
  // user nice system idle iowait irq softirq steal (guest time is inside user already)
  for (int field = 0; field < 8; ++field) {
    long long v = 0;
    in >> v;
    t.total += v;
    if (field == 7) t.steal = v;
  }
  return t;
}

std::string percent(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

// One rate: the empty loop paced for `seconds`, its figures added to the fragment.
void measure_empty_loop(int rate, double seconds, bool awake, bench::Fragment& fragment) {
  const std::string r = std::to_string(rate);
  const std::string how = awake ? "CPUs kept awake" : "CPUs free to idle";
  realtime::Pacer pacer(1'000'000'000LL / rate);
  realtime::LatencyHistogram lateness;
  const auto cycles = static_cast<std::int64_t>(seconds * rate);
  const CpuTimes before = read_cpu_times();
  pacer.start();
  while (pacer.cycles() < cycles) lateness.add(pacer.wait_next());
  const CpuTimes after = read_cpu_times();
  const double steal_pct = after.total > before.total ? 100.0 * static_cast<double>(after.steal - before.steal) /
                                                            static_cast<double>(after.total - before.total)
                                                      : 0.0;
  const double overruns_pct = 100.0 * static_cast<double>(pacer.overruns()) / static_cast<double>(pacer.cycles());
  const realtime::LatencySummary late = lateness.summary();
  const std::string id = "realtime_floor_" + r + "hz" + (awake ? "_awake" : "");
  bench::Figure f =
      bench::figure(id, "Empty paced loop (no work, no DDS), SCHED_FIFO, " + how + ": overruns at " + r + " Hz",
                    "% of cycles", bench::single(overruns_pct));
  if (rate == 4096) f.aiming_for("< 0.1 % (else the DDS target cannot be met on this host)", overruns_pct < 0.1);
  fragment.add(f);
  fragment.add(bench::figure(id + "_wakeup_p999", "  wake-up lateness p99.9", "us", bench::single(late.p999_s * 1e6)));
  fragment.add(bench::figure(id + "_wakeup_max", "  wake-up lateness max", "us", bench::single(late.max_s * 1e6)));
  fragment.add(
      bench::figure(id + "_steal", "  host steal time during the run", "% of CPU time", bench::single(steal_pct)));
  fragment.note(how + ", " + r + " Hz: " + std::to_string(pacer.cycles()) + " cycles, " +
                std::to_string(pacer.overruns()) + " overruns (" + percent(overruns_pct) + " %), " +
                std::to_string(pacer.skipped_deadlines()) + " deadlines skipped; wake-up p50 " +
                percent(late.p50_s * 1e6) + " us, p99 " + percent(late.p99_s * 1e6) + " us; steal " +
                percent(steal_pct) + " %");
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 1);
  std::vector<int> rates{1024, 2048, 4096};
  double seconds = 60.0;
  for (std::size_t i = 0; i + 1 < options.rest.size(); i += 2) {
    const std::string& key = options.rest[i];
    const std::string& value = options.rest[i + 1];
    if (key == "--seconds")
      seconds = std::stod(value);
    else if (key == "--rates")
      rates = bench::parse_rates(value);
    else
      throw std::invalid_argument("unknown option " + key);
  }
  if (options.rest.size() % 2 != 0) throw std::invalid_argument("unknown option " + options.rest.back());
  if (!(seconds > 0.0)) throw std::invalid_argument("--seconds: positive");
  bench::Fragment fragment("realtime_floor", argc, argv);

  const realtime::RealTimeSetupReport granted = realtime::apply_realtime({});
  if (!granted.refused.empty())
    fragment.note("real-time request refused, figures are for the default scheduler: " + granted.refused);

  for (const bool awake : {false, true}) {
    const realtime::CpuWakeLatencyHold hold = awake ? realtime::CpuWakeLatencyHold(0) : realtime::CpuWakeLatencyHold();
    if (awake && !hold.held()) {
      fragment.note("the CPUs could not be kept awake: " + hold.refused());
      break;
    }
    for (const int rate : rates) measure_empty_loop(rate, seconds, awake, fragment);
  }
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "realtime_floor: %s\n", e.what());
  return 1;
}
