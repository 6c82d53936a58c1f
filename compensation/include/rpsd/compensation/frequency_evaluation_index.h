// Frequency-domain evaluation index (FEI; Guo, Chen, Xu & Sanchez, Smart Mater. Struct. 2014,
// after the Freq_Resp_Tong.m script of RobustAMBCvRTHS):
//   FEI  = sum_f [O(f) / I(f)] |I(f)|^2 / sum_f |I(f)|^2 = sum_f O(f) conj(I(f)) / sum_f |I(f)|^2
//   A    = |FEI|,  phi = arg FEI,  f_eq = sum_f |I(f)|^2 f / sum_f |I(f)|^2,
//   delay = -phi / (2 pi f_eq)
// over the one-sided spectra of input I (target or command) and output O (measured) of an
// N-point FFT without padding or windowing: bins 0..floor(N/2), the interior ones doubled.
// The second form of FEI is the same sum written without the division, so bins where I = 0
// simply contribute nothing. Differences from the script: phi uses atan2 (the script's
// atan(Im/Re) folds leads and lags beyond a quarter period), and for even N the Nyquist bin is
// kept undoubled and the bin below it doubled (the script drops Nyquist and leaves bin N/2 - 1
// undoubled). Optional mean removal keeps a static offset (e.g. a free vibration that starts
// from a held displacement) from weighting the DC bin.
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
