// The floor under the real-time overrun figures: what this machine does to a paced loop that
// does nothing, measured as `rpsd host-check` measures a lab's PC (realtime/host_check.h):
// SCHED_FIFO 80 and locked memory as rpsd's loops ask, the empty loop at each control rate for
// --seconds, once with the CPUs free to idle and once kept awake. No loop with work in it can
// overrun less often on the same host, so this bounds what the 4096 Hz target of
// realtime_overruns can reach here. The host's steal time over each run is reported beside it.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "bench_report.h"
#include "rpsd/realtime/host_check.h"

namespace {

using namespace rpsd;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

void add_loop(const realtime::EmptyLoopFloor& l, bench::Fragment& fragment) {
  const std::string r = std::to_string(l.rate_hz);
  const std::string how = l.cpus_kept_awake ? "CPUs kept awake" : "CPUs free to idle";
  const std::string id = "realtime_floor_" + r + "hz" + (l.cpus_kept_awake ? "_awake" : "");
  const double overruns_pct = l.overruns_percent();
  bench::Figure f =
      bench::figure(id, "Empty paced loop (no work, no DDS), SCHED_FIFO, " + how + ": overruns at " + r + " Hz",
                    "% of cycles", bench::single(overruns_pct));
  if (l.rate_hz == 4096) f.aiming_for("< 0.1 % (else the DDS target cannot be met on this host)", overruns_pct < 0.1);
  fragment.add(f);
  fragment.add(
      bench::figure(id + "_wakeup_p999", "  wake-up lateness p99.9", "us", bench::single(l.wakeup.p999_s * 1e6)));
  fragment.add(bench::figure(id + "_wakeup_max", "  wake-up lateness max", "us", bench::single(l.wakeup.max_s * 1e6)));
  fragment.add(bench::figure(id + "_steal", "  host steal time during the run", "% of CPU time",
                             bench::single(l.steal_percent)));
  fragment.note(how + ", " + r + " Hz: " + std::to_string(l.cycles) + " cycles, " + std::to_string(l.overruns) +
                " overruns (" + number(overruns_pct) + " %), " + std::to_string(l.skipped_deadlines) +
                " deadlines skipped; wake-up p50 " + number(l.wakeup.p50_s * 1e6) + " us, p99 " +
                number(l.wakeup.p99_s * 1e6) + " us; steal " + number(l.steal_percent) + " %");
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 1);
  realtime::HostCheckRequest request;
  request.seconds_per_rate = 60.0;
  for (std::size_t i = 0; i + 1 < options.rest.size(); i += 2) {
    const std::string& key = options.rest[i];
    const std::string& value = options.rest[i + 1];
    if (key == "--seconds")
      request.seconds_per_rate = std::stod(value);
    else if (key == "--rates")
      request.rates_hz = bench::parse_rates(value);
    else
      throw std::invalid_argument("unknown option " + key);
  }
  if (options.rest.size() % 2 != 0) throw std::invalid_argument("unknown option " + options.rest.back());
  bench::Fragment fragment("realtime_floor", argc, argv);
  const realtime::HostCheckReport report = realtime::check_host(request);
  if (!report.granted.refused.empty())
    fragment.note("real-time request refused, figures are for the default scheduler: " + report.granted.refused);
  if (!report.cpus_could_be_kept_awake) fragment.note("the CPUs could not be kept awake: " + report.keep_awake_refused);
  fragment.note("kernel preemption: " + std::string(realtime::preemption_name(report.kernel.model)) + " (" +
                report.kernel.source + ")");
  for (const auto& loop : report.loops) add_loop(loop, fragment);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "realtime_floor: %s\n", e.what());
  return 1;
}
