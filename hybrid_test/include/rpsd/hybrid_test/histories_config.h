// What a test keeps of its histories (output.histories, docs/results-format.md): every step,
// none (the criteria only), or every k-th step by exact step index. The criteria are computed
// from every step whatever is kept; only what is written changes.
#pragma once

#include <cstdint>

namespace rpsd::hybrid_test {

struct HistoriesConfig {
  enum class Kept { kAll, kCriteriaOnly, kDecimated };
  Kept kept = Kept::kAll;
  // With kDecimated: the rate kept (output.history_rate_hz) and the steps between two kept
  // rows, control rate / rate, a whole number (rows are the steps n with n % every_steps == 0).
  double rate_hz = 0.0;
  std::int64_t every_steps = 1;

  bool written() const { return kept != Kept::kCriteriaOnly; }
};

// "all", "criteria_only" or "decimated", as output.histories names it.
const char* kept_name(HistoriesConfig::Kept kept);

}  // namespace rpsd::hybrid_test
