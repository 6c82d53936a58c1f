// Frequency-domain evaluation index (FEI; Guo, Chen, Xu & Sanchez, Smart Mater. Struct. 2014):
// FEI = sum_f O(f) conj(I(f)) / sum_f |I(f)|^2 over the spectra of input I and output O, whose modulus is
// the amplitude ratio and whose phase, at the input's energy-weighted frequency f_eq, gives the delay
// -arg FEI / (2 pi f_eq): how well the measured displacement follows its input, judged in frequency.
// Derivation, sources and differences from the original script: docs/compensation.md
#pragma once

#include <complex>
#include <span>
#include <vector>

#include <unsupported/Eigen/FFT>

namespace rpsd::compensation {

struct FrequencyEvaluationIndex {
  bool valid = false;  // false when the input has no energy (outside DC with mean removal)
  std::complex<double> index{0.0, 0.0};
  double amplitude = 0.0;
  double phase_rad = 0.0;
  double equivalent_frequency_hz = 0.0;
  double delay_s = 0.0;  // -phi / (2 pi f_eq); positive when the output lags
};

// Offline over whole records of equal length N >= 2. Throws std::invalid_argument on bad
// lengths or dt_s. Not real-time safe.
FrequencyEvaluationIndex frequency_evaluation_index(std::span<const double> input, std::span<const double> output,
                                                    double dt_s, bool remove_mean = false);

struct FrequencyEvaluationIndexParameters {
  double dt_s = 0.0;
  int window_samples = 4096;              // N of the FFT (any N >= 4; powers of 2 are fastest)
  int evaluation_interval_samples = 256;  // recompute every this many samples
  bool remove_mean = false;

  // Throws std::invalid_argument with the offending value. Not real-time safe.
  void validate() const;
};

// Online over a sliding window of N samples: update() stores the sample (O(1)); every
// evaluation_interval_samples-th update, once the window is full, it also evaluates FEI on the
// window (two real FFTs, O(N log N), on that step only). Buffers and the FFT plan are made in
// configure(), so update() does not allocate.
class FrequencyEvaluationIndexEstimator {
 public:
  // Sizes the buffers and plans the FFT. Throws std::invalid_argument. Not real-time safe.
  void configure(const FrequencyEvaluationIndexParameters& parameters);
  // Empties the window and forgets the last result. Real-time safe.
  void reset() noexcept;
  // Adds one sample of input and output. Real-time safe.
  void update(double input, double output) noexcept;
  // The latest evaluation (invalid before the first). Real-time safe.
  const FrequencyEvaluationIndex& latest() const noexcept { return latest_; }
  // Samples seen since reset. Real-time safe.
  long samples() const noexcept { return count_; }

 private:
  void evaluate() noexcept;

  FrequencyEvaluationIndexParameters parameters_;
  std::vector<double> input_ring_, output_ring_;
  std::vector<double> input_ordered_, output_ordered_;
  std::vector<std::complex<double>> input_spectrum_, output_spectrum_;
  Eigen::FFT<double> fft_;
  long count_ = 0;
  int since_evaluation_ = 0;
  FrequencyEvaluationIndex latest_;
};

}  // namespace rpsd::compensation
