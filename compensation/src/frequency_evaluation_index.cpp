#include "rpsd/compensation/frequency_evaluation_index.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "validation.h"

namespace rpsd::compensation {

namespace {

// Removes the mean of x in place when asked. Real-time safe.
void remove_mean_of(std::span<double> x) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  for (double& v : x) v -= mean;
}

// FEI from the half spectra (bins 0..N/2) of an N-point FFT. Real-time safe.
FrequencyEvaluationIndex combine(std::span<const std::complex<double>> in, std::span<const std::complex<double>> out,
                                 std::size_t n, double dt_s) {
  std::complex<double> cross = 0.0;
  double energy = 0.0;
  double weighted_frequency = 0.0;
  const double df = 1.0 / (static_cast<double>(n) * dt_s);
  const std::size_t last = n / 2;
  for (std::size_t k = 0; k <= last; ++k) {
    // One-sided amplitude: interior bins doubled; DC and (even N) Nyquist single.
    const double side = (k == 0 || (n % 2 == 0 && k == last)) ? 1.0 : 2.0;
    const std::complex<double> i1 = side * in[k];
    const std::complex<double> o1 = side * out[k];
    const double power = std::norm(i1);
    cross += o1 * std::conj(i1);
    energy += power;
    weighted_frequency += power * static_cast<double>(k) * df;
  }
  FrequencyEvaluationIndex r;
  if (!(energy > 0.0) || !(weighted_frequency > 0.0)) return r;
  r.valid = true;
  r.index = cross / energy;
  r.amplitude = std::abs(r.index);
  r.phase_rad = std::arg(r.index);
  r.equivalent_frequency_hz = weighted_frequency / energy;
  r.delay_s = -r.phase_rad / (2.0 * std::numbers::pi * r.equivalent_frequency_hz);
  return r;
}

}  // namespace

FrequencyEvaluationIndex frequency_evaluation_index(std::span<const double> input, std::span<const double> output,
                                                    double dt_s, bool remove_mean) {
  detail::require_positive("frequency evaluation index: dt_s", dt_s);
  if (input.size() != output.size()) {
    throw std::invalid_argument("frequency evaluation index: input and output lengths differ (" +
                                std::to_string(input.size()) + " vs " + std::to_string(output.size()) + ")");
  }
  if (input.size() < 2) detail::fail("frequency evaluation index: record length", "must be >= 2", input.size());
  std::vector<double> in(input.begin(), input.end()), out(output.begin(), output.end());
  if (remove_mean) {
    remove_mean_of(in);
    remove_mean_of(out);
  }
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  const std::size_t n = in.size();
  std::vector<std::complex<double>> in_spectrum(n / 2 + 1), out_spectrum(n / 2 + 1);
  fft.fwd(in_spectrum.data(), in.data(), static_cast<Eigen::Index>(n));
  fft.fwd(out_spectrum.data(), out.data(), static_cast<Eigen::Index>(n));
  return combine(in_spectrum, out_spectrum, n, dt_s);
}

void FrequencyEvaluationIndexParameters::validate() const {
  const std::string w = "frequency evaluation index estimator: ";
  detail::require_positive(w + "dt_s", dt_s);
  if (window_samples < 4) detail::fail(w + "window_samples", "must be >= 4", window_samples);
  if (evaluation_interval_samples < 1) {
    detail::fail(w + "evaluation_interval_samples", "must be >= 1", evaluation_interval_samples);
  }
}

void FrequencyEvaluationIndexEstimator::configure(const FrequencyEvaluationIndexParameters& parameters) {
  parameters.validate();
  parameters_ = parameters;
  const auto n = static_cast<std::size_t>(parameters.window_samples);
  input_ring_.assign(n, 0.0);
  output_ring_.assign(n, 0.0);
  input_ordered_.assign(n, 0.0);
  output_ordered_.assign(n, 0.0);
  input_spectrum_.assign(n / 2 + 1, 0.0);
  output_spectrum_.assign(n / 2 + 1, 0.0);
  fft_.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  // Warm-up: kissfft builds its plan, twiddles and scratch buffers on the first transform of
  // a size and reuses them afterwards.
  fft_.fwd(input_spectrum_.data(), input_ordered_.data(), static_cast<Eigen::Index>(n));
  reset();
}

void FrequencyEvaluationIndexEstimator::reset() noexcept {
  count_ = 0;
  since_evaluation_ = 0;
  latest_ = FrequencyEvaluationIndex{};
}

void FrequencyEvaluationIndexEstimator::update(double input, double output) noexcept {
  assert(!input_ring_.empty() && "configure() first");
  const long n = parameters_.window_samples;
  const auto slot = static_cast<std::size_t>(count_ % n);
  input_ring_[slot] = input;
  output_ring_[slot] = output;
  ++count_;
  if (count_ < n) return;
  if (count_ > n && ++since_evaluation_ < parameters_.evaluation_interval_samples) return;
  since_evaluation_ = 0;
  evaluate();
}

void FrequencyEvaluationIndexEstimator::evaluate() noexcept {
  const long n = parameters_.window_samples;
  const long start = count_ % n;  // the oldest sample in the ring
  for (long k = 0; k < n; ++k) {
    const auto from = static_cast<std::size_t>((start + k) % n);
    input_ordered_[static_cast<std::size_t>(k)] = input_ring_[from];
    output_ordered_[static_cast<std::size_t>(k)] = output_ring_[from];
  }
  if (parameters_.remove_mean) {
    remove_mean_of(input_ordered_);
    remove_mean_of(output_ordered_);
  }
  fft_.fwd(input_spectrum_.data(), input_ordered_.data(), static_cast<Eigen::Index>(n));
  fft_.fwd(output_spectrum_.data(), output_ordered_.data(), static_cast<Eigen::Index>(n));
  latest_ = combine(input_spectrum_, output_spectrum_, static_cast<std::size_t>(n), parameters_.dt_s);
}

}  // namespace rpsd::compensation
