// Cross-correlation delay (benchmark J1) on synthetic delayed signals, integer and
// fractional delays, offline and online.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rpsd/compensation/cross_correlation_delay.h"
#include "test_signals.h"

namespace rpsd::compensation {
namespace {

constexpr double kCorrelationStepS = 1.0 / 4096.0;
constexpr int kWindow = 4096;  // 1 s

// Tones at whole multiples of 1 Hz, so each is periodic over the 1 s window: the correlation is
// then exactly (W/2) sum A_i^2 cos(w_i (j - d) dt), whose maximum is at the true delay d.
const testing::MultiSine kSignal{{0.004, 0.003, 0.002, 0.001}, {3.0, 7.0, 11.0, 19.0}, {0.3, 1.9, 4.0, 0.8}};

struct Records {
  std::vector<double> target, measured;
};

Records delayed(double delay_samples, int length, double gain = 1.0, double offset = 0.0) {
  Records r;
  for (int k = 0; k < length; ++k) {
    r.target.push_back(kSignal(k * kCorrelationStepS));
    r.measured.push_back(offset + gain * kSignal((k - delay_samples) * kCorrelationStepS));
  }
  return r;
}

TEST(CrossCorrelationDelay, FindsIntegerDelaysExactly) {
  for (int d : {0, 1, 17, 33, 49}) {
    const Records r = delayed(d, kWindow + 49);
    const DelayEstimate e = cross_correlation_delay(r.target, r.measured);
    ASSERT_TRUE(e.valid);
    EXPECT_EQ(e.lag_samples, d);
    EXPECT_EQ(e.at_boundary, d == 0 || d == 49);
    EXPECT_NEAR(e.delay_samples, d, 1e-6) << d;
  }
}

TEST(CrossCorrelationDelay, RefinesFractionalDelaysToATenThousandthOfASample) {
  // Through three samples of cos(e (j - d)) around the peak, the parabola's vertex lies at
  // f + delta (1 + e^2 (delta^2 / 3 - 1/12) + ...) for the fractional part delta (|delta| <= 1/2)
  // and e = w dt <= 0.03 here: errors of order 1e-5 samples.
  for (double d : {5.5, 12.3, 30.75, 47.9}) {
    const Records r = delayed(d, kWindow + 49);
    const DelayEstimate e = cross_correlation_delay(r.target, r.measured);
    ASSERT_TRUE(e.valid);
    EXPECT_EQ(e.lag_samples, static_cast<int>(std::lround(d)));
    testing::record("error_samples_at_" + std::to_string(d), e.delay_samples - d);
    EXPECT_NEAR(e.delay_samples, d, 1e-4) << d;
    CrossCorrelationOptions integer_only;
    integer_only.subsample_refinement = false;
    EXPECT_EQ(cross_correlation_delay(r.target, r.measured, integer_only).delay_samples, std::lround(d));
  }
}

TEST(CrossCorrelationDelay, PearsonIgnoresGainAndOffset) {
  CrossCorrelationOptions pearson;
  pearson.measure = CorrelationMeasure::kPearson;
  const Records r = delayed(21.4, kWindow + 49, 0.7, 0.05);
  const DelayEstimate e = cross_correlation_delay(r.target, r.measured, pearson);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.delay_samples, 21.4, 1e-4);
  EXPECT_LE(e.peak, 1.0);
  EXPECT_GT(e.peak, 0.999);
}

TEST(CrossCorrelationDelay, ADelayBeyondTheSearchIsReportedAtTheBoundary) {
  const Records r = delayed(60.0, kWindow + 49);
  const DelayEstimate e = cross_correlation_delay(r.target, r.measured);
  EXPECT_TRUE(e.at_boundary);
  EXPECT_EQ(e.lag_samples, 49);
}

TEST(CrossCorrelationDelay, OnlineSlidingWindowAgreesWithOfflineAndTracksAChange) {
  CrossCorrelationDelayParameters p;
  p.window_samples = kWindow;
  for (CorrelationMeasure measure : {CorrelationMeasure::kProductSum, CorrelationMeasure::kPearson}) {
    p.options.measure = measure;
    CrossCorrelationDelayEstimator online;
    online.configure(p);
    // 3 s at 12.3 samples of delay, then 3 s at 26.6: the estimate follows once the window
    // has slid past the change.
    std::vector<double> last_target, last_measured;
    const int n_total = 6 * kWindow;
    for (int k = 0; k < n_total; ++k) {
      const double d = k < 3 * kWindow ? 12.3 : 26.6;
      const double t = kSignal(k * kCorrelationStepS), m = kSignal((k - d) * kCorrelationStepS);
      online.update(t, m);
      if (k == kWindow + 48) {
        ASSERT_TRUE(online.ready());
      } else if (k < kWindow + 48) {
        ASSERT_FALSE(online.ready());
      }
      if (k == 3 * kWindow - 1) {
        EXPECT_NEAR(online.estimate().delay_samples, 12.3, 1e-4);
      }
      if (k >= n_total - (kWindow + 49)) {
        last_target.push_back(t);
        last_measured.push_back(m);
      }
    }
    const DelayEstimate e = online.estimate();
    EXPECT_NEAR(e.delay_samples, 26.6, 1e-4);
    const DelayEstimate offline = cross_correlation_delay(last_target, last_measured, p.options);
    EXPECT_EQ(e.lag_samples, offline.lag_samples);
    EXPECT_NEAR(e.delay_samples, offline.delay_samples, 1e-9);
    EXPECT_NEAR(e.peak, offline.peak, 1e-9 * std::abs(offline.peak));
  }
}

// The definition summed lag by lag (S(j) over k = max_lag .. N-1), for the product sum.
std::vector<double> product_sums_by_definition(const Records& r, int max_lag) {
  std::vector<double> s(static_cast<std::size_t>(max_lag) + 1, 0.0);
  for (int j = 0; j <= max_lag; ++j) {
    for (std::size_t k = static_cast<std::size_t>(max_lag); k < r.target.size(); ++k) {
      s[static_cast<std::size_t>(j)] += r.measured[k] * r.target[k - static_cast<std::size_t>(j)];
    }
  }
  return s;
}

TEST(CrossCorrelationDelay, AccumulatorEqualsTheWholeRecordBitForBitAtEveryLength) {
  // A test is evaluated as it runs, without keeping its history: the accumulator after N
  // samples must give what the offline function gives on those N samples, exactly.
  const Records r = delayed(17.4, kWindow + 49);
  for (CorrelationMeasure measure : {CorrelationMeasure::kProductSum, CorrelationMeasure::kPearson}) {
    CrossCorrelationOptions options;
    options.measure = measure;
    CrossCorrelationAccumulator sums(options);
    EXPECT_FALSE(sums.estimate().valid);
    for (std::size_t k = 0; k < r.target.size(); ++k) {
      sums.add(r.target[k], r.measured[k]);
      const std::size_t n = k + 1;
      if (n < 52) {
        EXPECT_FALSE(sums.estimate().valid);
        continue;
      }
      if (!(n == 52 || n == 53 || n % 397 == 0 || n == r.target.size())) continue;
      const std::span<const double> t(r.target.data(), n), m(r.measured.data(), n);
      const DelayEstimate offline = cross_correlation_delay(t, m, options);
      const DelayEstimate online = sums.estimate();
      ASSERT_TRUE(online.valid);
      EXPECT_EQ(online.lag_samples, offline.lag_samples);
      EXPECT_EQ(online.delay_samples, offline.delay_samples);
      EXPECT_EQ(online.peak, offline.peak);
    }
    EXPECT_NEAR(sums.estimate().delay_samples, 17.4, 1e-3);
  }
  // The product sum is the definition's, bit for bit.
  CrossCorrelationAccumulator sums;
  for (std::size_t k = 0; k < r.target.size(); ++k) sums.add(r.target[k], r.measured[k]);
  const auto by_definition = product_sums_by_definition(r, 49);
  const DelayEstimate e = sums.estimate();
  EXPECT_EQ(e.peak, by_definition[static_cast<std::size_t>(e.lag_samples)]);
}

TEST(CrossCorrelationDelay, ASearchBelowZeroFindsALeadAsANegativeLag) {
  // Lags -49..49: each lag sums the same W = N - 98 products; a measurement ahead of its
  // target by d samples peaks at -d, refined as a delay is; one behind at +d.
  CrossCorrelationOptions both_ways;
  both_ways.min_lag_samples = -49;
  for (double d : {-30.75, -12.0, -0.4, 0.0, 17.0, 47.9}) {
    const Records r = delayed(d, kWindow + 98);
    const DelayEstimate e = cross_correlation_delay(r.target, r.measured, both_ways);
    ASSERT_TRUE(e.valid);
    EXPECT_EQ(e.lag_samples, static_cast<int>(std::lround(d))) << d;
    EXPECT_NEAR(e.delay_samples, d, 1e-4) << d;
    EXPECT_FALSE(e.at_boundary) << d;
  }
  const Records ahead = delayed(-60.0, kWindow + 98);
  const DelayEstimate e = cross_correlation_delay(ahead.target, ahead.measured, both_ways);
  EXPECT_TRUE(e.at_boundary);
  EXPECT_EQ(e.lag_samples, -49);
}

TEST(CrossCorrelationDelay, RejectsBadInput) {
  std::vector<double> a(100), b(99);
  EXPECT_THROW(cross_correlation_delay(a, b), std::invalid_argument);
  std::vector<double> tiny(40);
  EXPECT_THROW(cross_correlation_delay(tiny, tiny), std::invalid_argument);
  CrossCorrelationDelayParameters p;
  p.options.max_lag_samples = 0;
  CrossCorrelationDelayEstimator e;
  EXPECT_THROW(e.configure(p), std::invalid_argument);
  // The search's lower end is at most 0; the sliding window searches from 0 only.
  CrossCorrelationOptions above_zero;
  above_zero.min_lag_samples = 1;
  std::vector<double> long_record(200);
  EXPECT_THROW(cross_correlation_delay(long_record, long_record, above_zero), std::invalid_argument);
  CrossCorrelationDelayParameters both_ways;
  both_ways.options.min_lag_samples = -10;
  EXPECT_THROW(e.configure(both_ways), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
