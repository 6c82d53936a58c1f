// Latency and jitter statistics over runs of any length in constant memory: a histogram
// with 1 us bins up to 2 ms and 100 us bins up to 100 ms (an HDR-style layout), plus the
// exact maximum. Percentiles are exact to the bin width. Adding a sample is real-time safe.
#pragma once

#include <array>
#include <cstdint>

namespace rpsd::realtime {

struct LatencySummary {
  std::int64_t count = 0;
  double p50_s = 0.0, p99_s = 0.0, p999_s = 0.0, max_s = 0.0, mean_s = 0.0;
};

class LatencyHistogram {
 public:
  // Real-time safe. Negative samples count as zero.
  void add(std::int64_t ns);
  // `times` samples of 0 ns at once (a site in process answers in the same call), as that many
  // add(0) would: a 0 leaves the maximum and the sum as they are. Real-time safe.
  void add_zeros(std::int64_t times);
  // Upper edge of the bin holding quantile q in [0, 1] (0 when empty). Real-time safe.
  std::int64_t quantile_ns(double q) const;
  LatencySummary summary() const;
  std::int64_t count() const { return count_; }
  std::int64_t max_ns() const { return max_ns_; }
  void clear();

 private:
  static constexpr std::int64_t kFineBinNs = 1'000, kFineLimitNs = 2'000'000;
  static constexpr std::int64_t kCoarseBinNs = 100'000, kCoarseLimitNs = 100'000'000;
  static constexpr int kFineBins = kFineLimitNs / kFineBinNs;
  static constexpr int kBins = kFineBins + (kCoarseLimitNs - kFineLimitNs) / kCoarseBinNs + 1;  // + overflow
  static int bin_of(std::int64_t ns);
  static std::int64_t upper_edge_ns(int bin);

  std::array<std::int64_t, kBins> bins_{};
  std::int64_t count_ = 0, max_ns_ = 0;
  double sum_ns_ = 0.0;
};

}  // namespace rpsd::realtime
