// Cyclone's own latency tool as the baseline of rpsd's DDS figures: a `ddsperf pong` and a
// `ddsperf ping` process, run with the configuration rpsd uses, and its per-second
// round-trip percentiles. Not real-time safe (benchmark drivers only).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rpsd::bench {

// One per-second line of `ddsperf ping`:
//   [pid] 2.000  host:pid size 168 mean 81.365us min 19.526us 50% 27.070us 90% ... 99% 1351.550us max ... cnt 6042
// ddsperf prints half of each round trip (ddsperf.c, process_pong: `(tnow - source_timestamp) / 2`,
// a one-way estimate); these figures are whole round trips, twice what it prints, so that they
// compare with rpsd's command-to-feedback time.
struct DdsperfLine {
  double mean_us = 0.0, p50_us = 0.0, p99_us = 0.0, max_us = 0.0;
  long count = 0;  // round trips in that second
};

// Every round-trip line of ddsperf's output, in order (other lines are skipped).
std::vector<DdsperfLine> parse_ddsperf(const std::string& text);

// Closed-loop pings (a new one as soon as the pong is in): the seconds of round trip in one
// line's second, count x mean. About 1 when the figures are whole round trips, about 0.5 if
// they were ddsperf's printed halves: the check that they are read right.
double closed_loop_busy_s(const DdsperfLine& line);

struct DdsperfOptions {
  std::string program = "ddsperf";
  int domain = 0;
  int seconds = 10;              // how long ping runs (-D)
  std::string rate;              // e.g. "1024Hz"; empty: closed loop (a ping as soon as the pong is in)
  int size_bytes = 168;          // payload
  std::vector<std::string> env;  // e.g. CYCLONEDDS_URI=file://...
  std::vector<std::string> pong_prefix, ping_prefix;  // e.g. {"ip", "netns", "exec", NS}
};

struct DdsperfRun {
  std::vector<DdsperfLine> lines;  // without the first (discovery)
  std::string command;             // ping's, with pong's
};

// Runs pong waitset and ping waitset for options.seconds; logs in `work`. Throws
// std::runtime_error when ping fails or prints fewer than two round-trip lines.
DdsperfRun run_ddsperf(const DdsperfOptions& options, const std::filesystem::path& work);

}  // namespace rpsd::bench
