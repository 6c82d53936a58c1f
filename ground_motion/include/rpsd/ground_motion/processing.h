// Record processing: pure functions, each taking a record and a typed option struct and
// returning a new record (the input is left alone). Each appends a line to
// GroundMotionRecord::processing_steps. Invalid options throw RecordError naming the record
// and the option. None is real-time safe (they allocate); run them at configure time.
#pragma once

#include <optional>
#include <vector>

#include "rpsd/ground_motion/record.h"

namespace rpsd::ground_motion {

// Exactly one of the two must be set.
struct ScaleOptions {
  std::optional<double> factor;               // multiply every sample (any finite value)
  std::optional<double> target_pga_m_per_s2;  // > 0: multiply by target / |PGA|
};
GroundMotionRecord scale(const GroundMotionRecord& record, const ScaleOptions& options);

// Keeps the samples with start_s <= t <= end_s (times of the input record; a bound within
// 1e-9 of a step from a sample counts as on it). The kept first sample becomes t = 0.
struct TrimOptions {
  double start_s = 0.0;
  std::optional<double> end_s;  // unset: to the last sample
};
GroundMotionRecord trim(const GroundMotionRecord& record, const TrimOptions& options);

// Adds zeros: round(before_s / dt) samples before the first and round(after_s / dt) after
// the last (zeros after let a structure's free vibration and long-period spectra ring out).
struct PadOptions {
  double before_s = 0.0;
  double after_s = 0.0;
};
GroundMotionRecord pad(const GroundMotionRecord& record, const PadOptions& options);

// Resamples to dt_s by linear interpolation between samples, over [0, duration] of the
// input (the last new sample is the last grid point not after the input's last sample).
//
// Why linear: a PEER record is, by the convention every response-spectrum program and the
// exact piecewise-linear (Nigam-Jennings) solver here use, a piecewise-linear signal
// between its samples. Linear interpolation onto a finer integrator grid keeps exactly that
// signal (so a structure integrated on the fine grid sees the record the spectra describe),
// adds no Gibbs ringing at the record's ends or at its steps, has no delay, and reproduces
// every original sample exactly when dt_in / dt_s is an integer (computed with integer
// arithmetic). Its error against a smooth band-limited signal is at most
// dt_in^2 / 8 * max|a''| (for a sine of frequency f: (2 pi f dt_in)^2 / 8 of the amplitude).
// Linear interpolation does not low-pass filter, so downsampling (dt_s > dt_in) would
// alias: it is refused unless allow_downsampling is set.
struct ResampleOptions {
  double dt_s = 0.0;  // required, > 0: the integrator step
  bool allow_downsampling = false;
};
GroundMotionRecord resample(const GroundMotionRecord& record, const ResampleOptions& options);

// Baseline correction.
//  - remove_mean: subtract the mean acceleration.
//  - polynomial_displacement (default): integrate the record twice from rest, exactly for
//    the piecewise-linear signal (velocity_and_displacement below); fit the displacement
//    in least squares with c_2 t^2 + ... + c_p t^p (p = polynomial_order, 2..6; no constant
//    or linear term, so the corrected record still starts at rest); subtract the fit's
//    second derivative from the acceleration. With p = 3 this removes exactly any
//    acceleration offset and linear acceleration drift (a parabolic velocity drift).
enum class BaselineMethod { kRemoveMean, kPolynomialDisplacement };
struct BaselineCorrectionOptions {
  BaselineMethod method = BaselineMethod::kPolynomialDisplacement;
  int polynomial_order = 3;
};
GroundMotionRecord baseline_correct(const GroundMotionRecord& record, const BaselineCorrectionOptions& options);

// Ground velocity and displacement from rest, exact for acceleration linear between
// samples: v+ = v + h (a0 + a1) / 2, d+ = d + h v + h^2 (2 a0 + a1) / 6.
struct GroundMotionIntegrals {
  std::vector<double> velocity_m_per_s;
  std::vector<double> displacement_m;
};
GroundMotionIntegrals velocity_and_displacement(const GroundMotionRecord& record);

}  // namespace rpsd::ground_motion
