#include "rpsd/realtime/latency_histogram.h"

#include <gtest/gtest.h>

namespace rpsd::realtime {
namespace {

TEST(LatencyHistogram, QuantilesOfAUniformSetAreExactToTheBin) {
  LatencyHistogram h;
  for (int us = 1; us <= 1000; ++us) h.add(us * 1000 - 1);  // just below each microsecond edge
  EXPECT_EQ(h.count(), 1000);
  EXPECT_EQ(h.quantile_ns(0.5), 500'000);
  EXPECT_EQ(h.quantile_ns(0.99), 990'000);
  EXPECT_EQ(h.quantile_ns(0.999), 999'000);
  EXPECT_EQ(h.max_ns(), 999'999);
  EXPECT_NEAR(h.summary().mean_s, 500.5e-6 - 1e-9, 1e-12);
}

TEST(LatencyHistogram, CoarseBinsAndOverflowAreBoundedByTheExactMaximum) {
  LatencyHistogram h;
  h.add(5'050'000);                          // 5.05 ms: coarse bin (5.0, 5.1] ms
  EXPECT_EQ(h.quantile_ns(0.5), 5'050'000);  // the bin's edge is above the maximum
  h.add(250'000'000);                        // 250 ms: overflow
  EXPECT_EQ(h.quantile_ns(0.5), 5'100'000);
  EXPECT_EQ(h.quantile_ns(1.0), 250'000'000);
  EXPECT_DOUBLE_EQ(h.summary().max_s, 0.25);
}

TEST(LatencyHistogram, NegativeSamplesCountAsZeroAndClearEmpties) {
  LatencyHistogram h;
  h.add(-5);
  EXPECT_EQ(h.quantile_ns(0.5), 0);
  EXPECT_EQ(h.count(), 1);
  h.clear();
  EXPECT_EQ(h.count(), 0);
  EXPECT_EQ(h.summary().p99_s, 0.0);
}

}  // namespace
}  // namespace rpsd::realtime
