// `rpsd host-check [--rates 1024,2048,4096] [--seconds S] [--json]`: what a lab PC gives a
// real-time loop before a test runs on it (realtime/host_check.h; docs/realtime.md).
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "rpsd/commands.h"
#include "rpsd/realtime/host_check.h"

namespace rpsd::cli {
namespace {

struct HostCheckOptions {
  std::vector<int> rates_hz{1024, 2048, 4096};
  double seconds = 10.0;
  bool json = false;
};

std::string number(const char* pattern, double v) {
  char text[48];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

void print_text(const realtime::HostCheckReport& r) {
  std::cout << "real time: SCHED_FIFO " << r.request.fifo_priority << ' '
            << (r.granted.fifo_granted ? "granted" : "REFUSED") << ", mlockall "
            << (r.granted.memory_locked ? "granted" : "REFUSED") << '\n';
  if (!r.granted.refused.empty()) std::cout << r.granted.refused;
  std::cout << "kernel preemption: " << realtime::preemption_name(r.kernel.model) << " (" << r.kernel.source << ")";
  if (!realtime::preempts_for_real_time(r.kernel.model)) {
    std::cout << "\n  WARNING: a real-time thread may wait for other tasks' kernel code (a build's page faults and"
                 " file I/O) to reach a preemption point, milliseconds in every wake-up of the loop; boot with"
                 " preempt=full or use a PREEMPT_RT kernel (docs/realtime.md)";
  }
  std::cout << '\n';
  std::cout << "CPU idle: driver " << (r.idle.driver.empty() ? std::string("none") : r.idle.driver) << ", "
            << r.idle.cpus << " CPU(s); states of CPU 0:";
  if (r.idle.states.empty()) std::cout << " none listed";
  std::cout << '\n';
  for (const auto& s : r.idle.states) {
    std::cout << "  " << s.name << ": exit latency " << s.exit_latency_us << " us" << (s.disabled ? ", disabled" : "")
              << (s.can_be_disabled ? ", can be disabled" : "") << '\n';
  }
  std::cout << "keeping the CPUs awake (" << realtime::kPmQosDevice
            << " 0): " << (r.cpus_could_be_kept_awake ? "possible" : "REFUSED: " + r.keep_awake_refused)
            << "; limit in force before: " << r.wake_latency_limit_us << " us\n";
  std::cout << "empty paced loop, " << number("%g", r.request.seconds_per_rate) << " s per rate:\n";
  for (const auto& l : r.loops) {
    std::cout << "  " << l.rate_hz << " Hz, " << (l.cpus_kept_awake ? "CPUs kept awake:   " : "CPUs free to idle: ")
              << l.overruns << " overruns of " << l.cycles << " cycles (" << number("%.3g", l.overruns_percent())
              << " %), " << l.skipped_deadlines << " deadlines skipped; wake-up p50 "
              << number("%.1f", 1e6 * l.wakeup.p50_s) << " us, p99 " << number("%.1f", 1e6 * l.wakeup.p99_s)
              << " us, p99.9 " << number("%.1f", 1e6 * l.wakeup.p999_s) << " us, max "
              << number("%.1f", 1e6 * l.wakeup.max_s) << " us; steal " << number("%.3g", l.steal_percent) << " %\n";
  }
}

}  // namespace

void add_host_check(CLI::App& app) {
  auto options = std::make_shared<HostCheckOptions>();
  auto* cmd = app.add_subcommand("host-check", "Measure this host's real-time floor: an empty paced loop per rate");
  cmd->add_option("--rates", options->rates_hz, "Control rates in Hz, comma-separated (default 1024,2048,4096)")
      ->delimiter(',')
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--seconds", options->seconds, "Seconds per rate and idle setting (default 10)")
      ->check(CLI::Range(0.001, 86400.0));
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  cmd->callback([options] {
    realtime::HostCheckRequest request;
    request.rates_hz = options->rates_hz;
    request.seconds_per_rate = options->seconds;
    const realtime::HostCheckReport report = realtime::check_host(request);
    if (options->json)
      std::cout << realtime::host_check_json(report).dump(2) << '\n';
    else
      print_text(report);
  });
}

}  // namespace rpsd::cli
