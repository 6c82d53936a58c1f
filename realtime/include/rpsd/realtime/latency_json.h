// One latency summary as JSON, the same in a test's summary.json and a servo node's
// --summary file.
#pragma once

#include <nlohmann/json.hpp>

#include "rpsd/realtime/latency_histogram.h"

namespace rpsd::realtime {

inline nlohmann::json latency_json(const LatencySummary& l) {
  return {{"count", l.count},    {"p50_s", l.p50_s}, {"p99_s", l.p99_s},
          {"p99_9_s", l.p999_s}, {"max_s", l.max_s}, {"mean_s", l.mean_s}};
}

}  // namespace rpsd::realtime
