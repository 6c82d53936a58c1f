#include "rpsd/realtime/host_check.h"

#include <stdexcept>

#include "rpsd/realtime/cpu_wake_latency.h"
#include "rpsd/realtime/latency_json.h"

namespace rpsd::realtime {

HostCheckReport check_host(const HostCheckRequest& request) {
  if (request.rates_hz.empty()) throw std::invalid_argument("host check: no rate to measure");
  for (const int rate : request.rates_hz) {
    if (rate <= 0) throw std::invalid_argument("host check: a rate must be positive, got " + std::to_string(rate));
  }
  if (!(request.seconds_per_rate > 0.0)) throw std::invalid_argument("host check: the duration must be positive");
  HostCheckReport report;
  report.request = request;
  report.wake_latency_limit_us = current_cpu_wake_latency_limit_us();
  report.idle = read_idle_states();
  report.kernel = read_kernel_preemption();
  RealTimeRequest rt;
  rt.fifo_priority = request.fifo_priority;
  rt.keep_cpus_awake = false;  // the loops run once free to idle, then kept awake
  report.granted = apply_realtime(rt);
  for (const int rate : request.rates_hz)
    report.loops.push_back(measure_empty_loop(rate, request.seconds_per_rate, false));
  const CpuWakeLatencyHold hold(0);
  report.cpus_could_be_kept_awake = hold.held();
  report.keep_awake_refused = hold.refused();
  if (hold.held()) {
    for (const int rate : request.rates_hz)
      report.loops.push_back(measure_empty_loop(rate, request.seconds_per_rate, true));
  }
  return report;
}

nlohmann::json host_check_json(const HostCheckReport& report) {
  using nlohmann::json;
  json refused = json::array();
  std::string line;
  for (const char c : report.granted.refused) {
    if (c == '\n') {
      if (!line.empty()) refused.push_back(line);
      line.clear();
    } else {
      line += c;
    }
  }
  if (!line.empty()) refused.push_back(line);
  json states = json::array();
  for (const IdleState& s : report.idle.states) {
    states.push_back({{"name", s.name},
                      {"exit_latency_us", s.exit_latency_us},
                      {"disabled", s.disabled},
                      {"can_be_disabled", s.can_be_disabled}});
  }
  json loops = json::array();
  for (const EmptyLoopFloor& l : report.loops) {
    loops.push_back({{"rate_hz", l.rate_hz},
                     {"cpus_kept_awake", l.cpus_kept_awake},
                     {"cycles", l.cycles},
                     {"overruns", l.overruns},
                     {"overruns_percent", l.overruns_percent()},
                     {"skipped_deadlines", l.skipped_deadlines},
                     {"wakeup", latency_json(l.wakeup)},
                     {"steal_percent", l.steal_percent}});
  }
  return {{"rates_hz", report.request.rates_hz},
          {"seconds_per_rate", report.request.seconds_per_rate},
          {"granted",
           {{"sched_fifo", report.granted.fifo_granted},
            {"fifo_priority", report.request.fifo_priority},
            {"mlockall", report.granted.memory_locked},
            {"refused", refused}}},
          {"kernel",
           {{"preemption", preemption_name(report.kernel.model)},
            {"source", report.kernel.source},
            {"preempts_for_real_time", preempts_for_real_time(report.kernel.model)}}},
          {"cpu_idle",
           {{"driver", report.idle.driver},
            {"cpus", report.idle.cpus},
            {"states", states},
            {"can_keep_cpus_awake", report.cpus_could_be_kept_awake},
            {"keep_awake_refused", report.keep_awake_refused},
            {"wake_latency_limit_us", report.wake_latency_limit_us}}},
          {"loops", loops}};
}

}  // namespace rpsd::realtime
