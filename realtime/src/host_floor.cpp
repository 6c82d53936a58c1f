#include "rpsd/realtime/host_floor.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rpsd/realtime/pacer.h"

namespace rpsd::realtime {

CpuTimes parse_cpu_times(const std::string& proc_stat) {
  std::istringstream in(proc_stat);
  std::string label;
  in >> label;
  if (label != "cpu") throw std::runtime_error("/proc/stat: the first line is not the \"cpu\" line");
  CpuTimes t;
  // user nice system idle iowait irq softirq steal (guest time is inside user already)
  for (int field = 0; field < 8; ++field) {
    long long v = 0;
    if (!(in >> v)) break;  // an old kernel without steal: no steal
    t.total += v;
    if (field == 7) t.steal = v;
  }
  return t;
}

CpuTimes read_cpu_times() {
  std::ifstream in("/proc/stat");
  std::string line;
  if (!std::getline(in, line)) return {};
  return parse_cpu_times(line);
}

double steal_percent(const CpuTimes& before, const CpuTimes& after) {
  if (after.total <= before.total) return 0.0;
  return 100.0 * static_cast<double>(after.steal - before.steal) / static_cast<double>(after.total - before.total);
}

double EmptyLoopFloor::overruns_percent() const {
  return cycles > 0 ? 100.0 * static_cast<double>(overruns) / static_cast<double>(cycles) : 0.0;
}

EmptyLoopFloor measure_empty_loop(int rate_hz, double seconds, bool cpus_kept_awake) {
  if (rate_hz <= 0) throw std::invalid_argument("empty loop: the rate must be positive");
  if (!(seconds > 0.0)) throw std::invalid_argument("empty loop: the duration must be positive");
  Pacer pacer(1'000'000'000LL / rate_hz);
  const auto cycles = static_cast<std::int64_t>(seconds * rate_hz);
  const CpuTimes before = read_cpu_times();
  EmptyLoopFloor floor = tally_empty_loop(pacer, rate_hz, cycles > 0 ? cycles : 1);
  floor.steal_percent = steal_percent(before, read_cpu_times());
  floor.cpus_kept_awake = cpus_kept_awake;
  return floor;
}

namespace {

std::string first_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

IdleStates read_idle_states(const std::string& cpu_root) {
  namespace fs = std::filesystem;
  IdleStates idle;
  const fs::path root(cpu_root);
  idle.driver = first_line(root / "cpuidle" / "current_driver");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    const std::string name = entry.path().filename();
    if (name.rfind("cpu", 0) == 0 && name.size() > 3 && name.find_first_not_of("0123456789", 3) == std::string::npos &&
        fs::is_directory(entry.path() / "cpuidle", ec))
      ++idle.cpus;
  }
  // stateN in order of N (a directory listing has no order).
  for (int n = 0;; ++n) {
    const fs::path state = root / "cpu0" / "cpuidle" / ("state" + std::to_string(n));
    if (!fs::is_directory(state, ec)) break;
    IdleState s;
    s.name = first_line(state / "name");
    const std::string latency = first_line(state / "latency");
    if (!latency.empty()) {
      try {
        s.exit_latency_us = std::stoi(latency);
      } catch (const std::exception&) {
        s.exit_latency_us = -1;
      }
    }
    s.disabled = first_line(state / "disable") == "1";
    s.can_be_disabled = ::access((state / "disable").c_str(), W_OK) == 0;
    idle.states.push_back(s);
  }
  return idle;
}

}  // namespace rpsd::realtime
