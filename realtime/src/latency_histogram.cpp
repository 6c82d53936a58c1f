#include "rpsd/realtime/latency_histogram.h"

#include <algorithm>
#include <cmath>

namespace rpsd::realtime {

int LatencyHistogram::bin_of(std::int64_t ns) {
  if (ns < kFineLimitNs) return static_cast<int>(ns / kFineBinNs);
  if (ns < kCoarseLimitNs) return kFineBins + static_cast<int>((ns - kFineLimitNs) / kCoarseBinNs);
  return kBins - 1;
}

std::int64_t LatencyHistogram::upper_edge_ns(int bin) {
  if (bin < kFineBins) return (bin + 1) * kFineBinNs;
  return kFineLimitNs + (bin - kFineBins + 1) * kCoarseBinNs;
}

void LatencyHistogram::add(std::int64_t ns) {
  ns = std::max<std::int64_t>(ns, 0);
  ++bins_[bin_of(ns)];
  ++count_;
  max_ns_ = std::max(max_ns_, ns);
  sum_ns_ += static_cast<double>(ns);
}

void LatencyHistogram::add_zeros(std::int64_t times) {
  if (times <= 0) return;
  bins_[bin_of(0)] += times;
  count_ += times;
}

std::int64_t LatencyHistogram::quantile_ns(double q) const {
  if (count_ == 0) return 0;
  const auto rank = static_cast<std::int64_t>(std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(count_)));
  std::int64_t seen = 0;
  for (int b = 0; b < kBins; ++b) {
    seen += bins_[b];
    // The overflow bin and the bin of the maximum are bounded by the exact maximum.
    if (seen >= std::max<std::int64_t>(rank, 1)) return b == kBins - 1 ? max_ns_ : std::min(upper_edge_ns(b), max_ns_);
  }
  return max_ns_;
}

LatencySummary LatencyHistogram::summary() const {
  LatencySummary s;
  s.count = count_;
  if (count_ == 0) return s;
  s.p50_s = quantile_ns(0.5) * 1e-9;
  s.p99_s = quantile_ns(0.99) * 1e-9;
  s.p999_s = quantile_ns(0.999) * 1e-9;
  s.max_s = max_ns_ * 1e-9;
  s.mean_s = sum_ns_ / static_cast<double>(count_) * 1e-9;
  return s;
}

void LatencyHistogram::clear() {
  bins_.fill(0);
  count_ = max_ns_ = 0;
  sum_ns_ = 0.0;
}

}  // namespace rpsd::realtime
