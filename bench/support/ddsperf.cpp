#include "ddsperf.h"

#include <csignal>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "child_process.h"

namespace rpsd::bench {
namespace {

double to_us(const std::string& number, const std::string& unit) {
  const double v = std::stod(number);
  if (unit == "ns") return v * 1e-3;
  if (unit == "us") return v;
  if (unit == "ms") return v * 1e3;
  if (unit == "s") return v * 1e6;
  throw std::runtime_error("ddsperf: unknown unit " + unit);
}

}  // namespace

std::vector<DdsperfLine> parse_ddsperf(const std::string& text) {
  static const std::regex line_re(
      R"( size \d+ mean ([0-9.]+)(ns|us|ms|s) min \S+ 50% ([0-9.]+)(ns|us|ms|s) 90% \S+ 99% ([0-9.]+)(ns|us|ms|s) max ([0-9.]+)(ns|us|ms|s) cnt (\d+))");
  std::vector<DdsperfLine> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, line_re)) continue;
    // Printed: half of each round trip (ddsperf.h).
    const auto round_trip_us = [&](int i) { return 2.0 * to_us(m[i], m[i + 1]); };
    lines.push_back({round_trip_us(1), round_trip_us(3), round_trip_us(5), round_trip_us(7), std::stol(m[9])});
  }
  return lines;
}

double closed_loop_busy_s(const DdsperfLine& line) { return static_cast<double>(line.count) * line.mean_us * 1e-6; }

DdsperfRun run_ddsperf(const DdsperfOptions& o, const std::filesystem::path& work) {
  const auto pong_log = work / "pong.log", ping_log = work / "ping.log";
  std::filesystem::remove(pong_log);
  std::filesystem::remove(ping_log);
  std::vector<std::string> pong_argv = o.pong_prefix;
  pong_argv.insert(pong_argv.end(), {o.program, "-i", std::to_string(o.domain), "pong", "waitset"});
  ChildProcess pong(pong_argv, o.env, pong_log);
  std::vector<std::string> ping_argv = o.ping_prefix;
  ping_argv.insert(ping_argv.end(),
                   {o.program, "-i", std::to_string(o.domain), "-D", std::to_string(o.seconds), "ping"});
  if (!o.rate.empty()) ping_argv.push_back(o.rate);
  ping_argv.insert(ping_argv.end(), {"size", std::to_string(o.size_bytes), "waitset"});
  ChildProcess ping(ping_argv, o.env, ping_log);
  const int code = ping.wait_for(o.seconds + 30.0);
  pong.stop(SIGTERM, 5.0);
  const std::string text = read_text(ping_log);
  if (code != 0) throw std::runtime_error("ddsperf ping failed (exit " + std::to_string(code) + "): " + text);
  DdsperfRun run;
  run.command = ping.command() + "  (with " + pong.command() + ")";
  run.lines = parse_ddsperf(text);
  if (run.lines.size() < 2) throw std::runtime_error("ddsperf printed fewer than two round-trip lines:\n" + text);
  run.lines.erase(run.lines.begin());
  return run;
}

}  // namespace rpsd::bench
