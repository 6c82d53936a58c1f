#include "rpsd/compensation/cross_correlation_delay.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "validation.h"

namespace rpsd::compensation {

namespace {

// Sums of one lag over a window of W products; the shared data the two measures need.
struct LagSums {
  double product = 0.0;
  double target = 0.0;
  double target_square = 0.0;
};

double measure_value(CorrelationMeasure measure, const LagSums& s, double measured_sum, double measured_square_sum,
                     double w) {
  if (measure == CorrelationMeasure::kProductSum) return s.product;
  const double cov = w * s.product - measured_sum * s.target;
  const double var_m = w * measured_square_sum - measured_sum * measured_sum;
  const double var_t = w * s.target_square - s.target * s.target;
  if (!(var_m > 0.0) || !(var_t > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return cov / std::sqrt(var_m * var_t);
}

// Picks the maximum of values[min_lag..max_lag] and refines it. From 0 (the benchmark's J1)
// it is the first maximum. A window on both sides of 0 is scanned outwards from 0 and a lag
// further out must beat the best by more than rounding: a periodic signal correlates equally
// a period away, and the delay is the peak nearest 0. Real-time safe.
template <typename ValueAt>
DelayEstimate pick_peak(int min_lag, int max_lag, bool refine, ValueAt value_at) {
  DelayEstimate e;
  const double tolerance = min_lag < 0 ? 1e-9 : 0.0;  // relative
  double best = 0.0;
  bool found = false;
  int best_lag = 0;
  for (int reach = 0; reach <= std::max(-min_lag, max_lag); ++reach) {
    for (const int j : {-reach, reach}) {
      if (j < min_lag || j > max_lag || (reach == 0 && found)) continue;
      const double v = value_at(j);
      if (!std::isfinite(v)) return e;  // a flat segment: Pearson undefined
      if (!found || v > best + tolerance * std::abs(best)) {
        best = v;
        best_lag = j;
        found = true;
      }
    }
  }
  e.valid = true;
  e.lag_samples = best_lag;
  e.delay_samples = best_lag;
  e.peak = best;
  e.at_boundary = best_lag == min_lag || best_lag == max_lag;
  if (refine && !e.at_boundary) {
    const double minus = value_at(best_lag - 1);
    const double plus = value_at(best_lag + 1);
    const double curvature = minus - 2.0 * best + plus;
    if (curvature < 0.0) e.delay_samples = best_lag + 0.5 * (minus - plus) / curvature;
  }
  return e;
}

void validate_options(const CrossCorrelationOptions& o, const std::string& what) {
  if (o.max_lag_samples < 1) detail::fail(what + ": max_lag_samples", "must be >= 1", o.max_lag_samples);
  if (o.min_lag_samples > 0) detail::fail(what + ": min_lag_samples", "must be <= 0", o.min_lag_samples);
}

}  // namespace

DelayEstimate cross_correlation_delay(std::span<const double> target_m, std::span<const double> measured_m,
                                      const CrossCorrelationOptions& options) {
  const std::string what = "cross-correlation delay";
  validate_options(options, what);
  if (target_m.size() != measured_m.size()) {
    throw std::invalid_argument(what + ": target and measured lengths differ (" + std::to_string(target_m.size()) +
                                " vs " + std::to_string(measured_m.size()) + ")");
  }
  const auto lag = static_cast<std::size_t>(options.max_lag_samples - options.min_lag_samples);
  if (target_m.size() < lag + 3) {
    detail::fail(what + ": record length",
                 "must exceed max_lag_samples - min_lag_samples + 2 = " + std::to_string(lag + 2),
                 static_cast<double>(target_m.size()));
  }
  CrossCorrelationAccumulator sums(options);
  for (std::size_t k = 0; k < target_m.size(); ++k) sums.add(target_m[k], measured_m[k]);
  return sums.estimate();
}

CrossCorrelationAccumulator::CrossCorrelationAccumulator(const CrossCorrelationOptions& options)
    : options_(options), lag_(0), lead_(0) {
  validate_options(options, "cross-correlation accumulator");
  lag_ = static_cast<std::size_t>(options.max_lag_samples - options.min_lag_samples);
  lead_ = static_cast<std::size_t>(-options.min_lag_samples);
  recent_targets_.assign(2 * (lag_ + 1), 0.0);
  recent_measured_.assign(lead_ + 1, 0.0);
  product_sum_.assign(lag_ + 1, 0.0);
  if (options.measure == CorrelationMeasure::kPearson) {
    target_sum_.assign(lag_ + 1, 0.0);
    target_square_sum_.assign(lag_ + 1, 0.0);
  }
}

void CrossCorrelationAccumulator::add(double target_m, double new_measured_m) noexcept {
  // Over the whole record the sums run over k = span .. N-1 (span = max_lag - min_lag), so
  // that every lag has the same W = N - span products: S(j) += x_m(k - lead) x_t(k - lead - j),
  // lead = -min_lag, so that a lag down to min_lag finds its target already added.
  const std::size_t slot = count_ % (lag_ + 1);
  recent_targets_[slot] = recent_targets_[slot + lag_ + 1] = target_m;
  recent_measured_[count_ % (lead_ + 1)] = new_measured_m;
  const double measured_m = recent_measured_[(count_ + 1) % (lead_ + 1)];  // x_m(k - lead)
  ++count_;
  if (count_ <= lag_) return;
  const double* t = recent_targets_.data() + slot + 1;  // t[i] = x_t(k - (span - i)), lag max_lag - i
  for (std::size_t i = 0; i <= lag_; ++i) product_sum_[i] += measured_m * t[i];
  if (!target_sum_.empty()) {
    for (std::size_t i = 0; i <= lag_; ++i) {
      target_sum_[i] += t[i];
      target_square_sum_[i] += t[i] * t[i];
    }
  }
  measured_sum_ += measured_m;
  measured_square_sum_ += measured_m * measured_m;
}

DelayEstimate CrossCorrelationAccumulator::estimate() const noexcept {
  if (count_ < lag_ + 3) return DelayEstimate{};
  const double w = static_cast<double>(count_ - lag_);
  const bool pearson = !target_sum_.empty();
  return pick_peak(options_.min_lag_samples, options_.max_lag_samples, options_.subsample_refinement, [&](int j) {
    const auto i = static_cast<std::size_t>(options_.max_lag_samples - j);
    const LagSums s{product_sum_[i], pearson ? target_sum_[i] : 0.0, pearson ? target_square_sum_[i] : 0.0};
    return measure_value(options_.measure, s, measured_sum_, measured_square_sum_, w);
  });
}

void CrossCorrelationDelayParameters::validate() const {
  validate_options(options, "cross-correlation delay estimator");
  if (options.min_lag_samples != 0) {
    detail::fail("cross-correlation delay estimator: min_lag_samples", "must be 0 (lags from 0 only)",
                 options.min_lag_samples);
  }
  if (window_samples < 3)
    detail::fail("cross-correlation delay estimator: window_samples", "must be >= 3", window_samples);
}

void CrossCorrelationDelayEstimator::configure(const CrossCorrelationDelayParameters& parameters) {
  parameters.validate();
  parameters_ = parameters;
  window_ = parameters.window_samples;
  max_lag_ = parameters.options.max_lag_samples;
  target_capacity_ = window_ + max_lag_ + 1;
  target_.assign(static_cast<std::size_t>(target_capacity_), 0.0);
  measured_.assign(static_cast<std::size_t>(window_), 0.0);
  product_sum_.assign(static_cast<std::size_t>(max_lag_ + 1), 0.0);
  target_sum_.assign(static_cast<std::size_t>(max_lag_ + 1), 0.0);
  target_square_sum_.assign(static_cast<std::size_t>(max_lag_ + 1), 0.0);
  reset();
}

void CrossCorrelationDelayEstimator::reset() noexcept {
  std::fill(product_sum_.begin(), product_sum_.end(), 0.0);
  std::fill(target_sum_.begin(), target_sum_.end(), 0.0);
  std::fill(target_square_sum_.begin(), target_square_sum_.end(), 0.0);
  measured_sum_ = 0.0;
  measured_square_sum_ = 0.0;
  count_ = 0;
  next_refresh_ = 0;
}

void CrossCorrelationDelayEstimator::update(double target_m, double measured_m) noexcept {
  assert(!target_.empty() && "configure() first");
  const long n = count_;
  const long oldest = n - window_;  // the sample leaving the window, if any
  const double leaving_measured = oldest >= 0 ? measured_at(oldest) : 0.0;
  target_[static_cast<std::size_t>(n % target_capacity_)] = target_m;
  measured_[static_cast<std::size_t>(n % window_)] = measured_m;
  for (int j = 0; j <= max_lag_; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (n - j >= 0) {
      const double t = target_at(n - j);
      product_sum_[u] += measured_m * t;
      target_sum_[u] += t;
      target_square_sum_[u] += t * t;
    }
    if (oldest - j >= 0) {
      const double t = target_at(oldest - j);
      product_sum_[u] -= leaving_measured * t;
      target_sum_[u] -= t;
      target_square_sum_[u] -= t * t;
    }
  }
  measured_sum_ += measured_m;
  measured_square_sum_ += measured_m * measured_m;
  if (oldest >= 0) {
    measured_sum_ -= leaving_measured;
    measured_square_sum_ -= leaving_measured * leaving_measured;
  }
  ++count_;
  if (ready()) refresh_one();
}

void CrossCorrelationDelayEstimator::refresh_one() noexcept {
  // Recompute one lag's sums (or, in turn, the measured sums) exactly over the window.
  const long first = count_ - window_;
  if (next_refresh_ <= max_lag_) {
    const auto j = static_cast<std::size_t>(next_refresh_);
    LagSums s;
    for (long k = first; k < count_; ++k) {
      const double t = target_at(k - next_refresh_);
      s.product += measured_at(k) * t;
      s.target += t;
      s.target_square += t * t;
    }
    product_sum_[j] = s.product;
    target_sum_[j] = s.target;
    target_square_sum_[j] = s.target_square;
  } else {
    double sum = 0.0, square = 0.0;
    for (long k = first; k < count_; ++k) {
      sum += measured_at(k);
      square += measured_at(k) * measured_at(k);
    }
    measured_sum_ = sum;
    measured_square_sum_ = square;
  }
  next_refresh_ = next_refresh_ > max_lag_ ? 0 : next_refresh_ + 1;
}

DelayEstimate CrossCorrelationDelayEstimator::estimate() const noexcept {
  if (!ready()) return DelayEstimate{};
  const double w = static_cast<double>(window_);
  return pick_peak(0, max_lag_, parameters_.options.subsample_refinement, [&](int j) {
    const auto u = static_cast<std::size_t>(j);
    return measure_value(parameters_.options.measure, LagSums{product_sum_[u], target_sum_[u], target_square_sum_[u]},
                         measured_sum_, measured_square_sum_, w);
  });
}

}  // namespace rpsd::compensation
