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

TEST(LatencyHistogram, ZerosAddedAtOnceGiveTheSummaryOfAddingEachOne) {
  // The test assembly counts an in-process site's 0 s round trips and adds them at the end.
  LatencyHistogram one_by_one, at_once;
  for (const std::int64_t ns : {0, 1'500, 0, 0, 3'200'000, 0, 700, 0}) {
    one_by_one.add(ns);
    if (ns != 0) at_once.add(ns);
  }
  at_once.add_zeros(5);
  at_once.add_zeros(0);
  const LatencySummary a = one_by_one.summary(), b = at_once.summary();
  EXPECT_EQ(b.count, a.count);
  EXPECT_EQ(b.p50_s, a.p50_s);
  EXPECT_EQ(b.p99_s, a.p99_s);
  EXPECT_EQ(b.p999_s, a.p999_s);
  EXPECT_EQ(b.max_s, a.max_s);
  EXPECT_EQ(b.mean_s, a.mean_s);
  EXPECT_EQ(at_once.quantile_ns(0.6), one_by_one.quantile_ns(0.6));  // the zeros' bin holds five
  LatencyHistogram zeros;
  zeros.add_zeros(3);
  EXPECT_EQ(zeros.summary().count, 3);
  EXPECT_EQ(zeros.summary().max_s, 0.0);
  EXPECT_EQ(zeros.summary().mean_s, 0.0);
}

}  // namespace
}  // namespace rpsd::realtime
