// Tracking delay by cross-correlation (RTHS benchmark criterion J1): the shift j in
// [min_lag, max_lag] samples that maximises the correlation of the measured displacement j
// samples later with the target, S(j) = sum_k x_m(k + j) x_t(k) (or the Pearson coefficient),
// every lag over the same W products, optionally refined to a fraction of a sample. A negative
// lag is a measurement that leads its target. Offline, streaming and sliding-window forms.
// Derivation and sources: docs/compensation.md
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rpsd::compensation {

enum class CorrelationMeasure { kProductSum, kPearson };

struct DelayEstimate {
  bool valid = false;          // false until enough samples, or for a flat/degenerate signal
  int lag_samples = 0;         // the maximising integer shift
  double delay_samples = 0.0;  // refined (or equal to lag_samples)
  bool at_boundary = false;    // the maximum is at min_lag or max_lag: the true delay may lie outside
  double peak = 0.0;           // S or the Pearson coefficient at lag_samples
};

struct CrossCorrelationOptions {
  int max_lag_samples = 49;  // the benchmark searches 0..49 samples at 4096 Hz
  // The search's other end, <= 0: below zero the measurement may lead its target. The
  // sliding-window estimator searches from 0 only.
  int min_lag_samples = 0;
  CorrelationMeasure measure = CorrelationMeasure::kProductSum;
  bool subsample_refinement = true;
};

// Offline over whole records of equal length N > max_lag + 2. Throws std::invalid_argument
// on bad lengths or options. Not real-time safe.
DelayEstimate cross_correlation_delay(std::span<const double> target_m, std::span<const double> measured_m,
                                      const CrossCorrelationOptions& options = {});

// cross_correlation_delay() over a record that arrives one sample at a time: after N samples
// estimate() equals cross_correlation_delay() of those N samples bit for bit (it is how that
// function computes), in O(max_lag) memory and O(max_lag) time per sample, so that a test of
// any length is evaluated without keeping its history.
class CrossCorrelationAccumulator {
 public:
  // Throws std::invalid_argument on bad options. Not real-time safe.
  explicit CrossCorrelationAccumulator(const CrossCorrelationOptions& options = {});
  // Adds sample k = samples(). Real-time safe.
  void add(double target_m, double measured_m) noexcept;
  std::size_t samples() const noexcept { return count_; }
  // The delay over every sample added; invalid until there are more than max_lag + 2.
  // Real-time safe.
  DelayEstimate estimate() const noexcept;

 private:
  CrossCorrelationOptions options_;
  std::size_t lag_;   // the span max_lag - min_lag
  std::size_t lead_;  // -min_lag: each measurement meets the targets up to lead_ samples after it
  // The last span + 1 targets, stored twice so that x_t(k - span .. k) is contiguous, and the
  // last lead + 1 measurements.
  std::vector<double> recent_targets_, recent_measured_;
  // Per lag, in reverse order (index max_lag - j), so the inner loop runs forward.
  std::vector<double> product_sum_, target_sum_, target_square_sum_;
  double measured_sum_ = 0.0, measured_square_sum_ = 0.0;
  std::size_t count_ = 0;
};

struct CrossCorrelationDelayParameters {
  CrossCorrelationOptions options;
  int window_samples = 4096;  // W products per lag

  // Throws std::invalid_argument unless 1 <= max_lag and window_samples >= 3. Not real-time safe.
  void validate() const;
};

// Online over a sliding window: per sample O(max_lag) to update the running sums of every
// lag, plus O(W) to recompute one lag's sums exactly (round robin, so rounding drift is
// cleared every max_lag + 2 samples); estimate() is O(max_lag). Fixed buffers.
class CrossCorrelationDelayEstimator {
 public:
  // Sizes the buffers. Throws std::invalid_argument. Not real-time safe.
  void configure(const CrossCorrelationDelayParameters& parameters);
  // Empties the window. Real-time safe.
  void reset() noexcept;
  // Adds one sample. Real-time safe.
  void update(double target_m, double measured_m) noexcept;
  // True once W + max_lag samples have been seen. Real-time safe.
  bool ready() const noexcept { return count_ >= window_ + max_lag_; }
  // The delay over the current window (invalid until ready()). Real-time safe.
  DelayEstimate estimate() const noexcept;

 private:
  double target_at(long k) const { return target_[static_cast<std::size_t>(k % target_capacity_)]; }
  double measured_at(long k) const { return measured_[static_cast<std::size_t>(k % window_)]; }
  void refresh_one() noexcept;

  CrossCorrelationDelayParameters parameters_;
  long window_ = 1;
  int max_lag_ = 0;
  long target_capacity_ = 1;
  std::vector<double> target_;       // ring of W + max_lag + 1 targets
  std::vector<double> measured_;     // ring of W measurements
  std::vector<double> product_sum_;  // per lag j: sum x_m(k) x_t(k - j) over the window
  std::vector<double> target_sum_;   // per lag j: sum x_t(k - j)
  std::vector<double> target_square_sum_;
  double measured_sum_ = 0.0;
  double measured_square_sum_ = 0.0;
  long count_ = 0;
  int next_refresh_ = 0;
};

}  // namespace rpsd::compensation
