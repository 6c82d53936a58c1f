#include "rpsd/ground_motion/processing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "no_fp_contract.h"
#include "rpsd/ground_motion/record_error.h"

namespace rpsd::ground_motion {
namespace {

// Sample-grid comparisons allow this fraction of a step for times typed in decimal.
constexpr double kGridTolerance = 1e-9;

std::string text_of(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

[[noreturn]] void fail(const GroundMotionRecord& record, const std::string& what) {
  throw RecordError(record.source + ": " + what);
}

void require_samples(const GroundMotionRecord& record, const char* operation) {
  if (record.acceleration_m_per_s2.empty() || !(record.dt_s > 0.0)) {
    fail(record, std::string(operation) + ": the record is empty or has no positive dt");
  }
}

}  // namespace

GroundMotionRecord scale(const GroundMotionRecord& record, const ScaleOptions& options) {
  require_samples(record, "scale");
  if (options.factor.has_value() == options.target_pga_m_per_s2.has_value()) {
    fail(record, "scale: expected exactly one of factor and target_pga_m_per_s2");
  }
  double factor = 0.0;
  GroundMotionRecord out = record;
  if (options.factor) {
    if (!std::isfinite(*options.factor)) fail(record, "scale.factor: expected a finite number");
    factor = *options.factor;
    out.processing_steps.push_back("scaled by " + text_of(factor));
  } else {
    const double target = *options.target_pga_m_per_s2;
    if (!(target > 0.0) || !std::isfinite(target)) {
      fail(record, "scale.target_pga_m_per_s2: expected a positive number, got " + text_of(target));
    }
    const double pga = std::abs(peak_ground_acceleration(record).value_m_per_s2);
    if (!(pga > 0.0)) fail(record, "scale.target_pga_m_per_s2: the record is all zeros");
    factor = target / pga;
    out.processing_steps.push_back("scaled by " + text_of(factor) + " to PGA " + text_of(target) + " m/s^2");
  }
  for (double& a : out.acceleration_m_per_s2) a *= factor;
  return out;
}

GroundMotionRecord trim(const GroundMotionRecord& record, const TrimOptions& options) {
  require_samples(record, "trim");
  const double last_time = record.duration_s();
  if (!(options.start_s >= 0.0) || !std::isfinite(options.start_s)) {
    fail(record, "trim.start_s: expected a time >= 0 s, got " + text_of(options.start_s));
  }
  const double end_s = options.end_s.value_or(last_time);
  if (!std::isfinite(end_s) || end_s > last_time + kGridTolerance * record.dt_s) {
    fail(record,
         "trim.end_s: " + text_of(end_s) + " s is after the record's last sample at " + text_of(last_time) + " s");
  }
  const double first_index = std::ceil(options.start_s / record.dt_s - kGridTolerance);
  const double last_index = std::floor(end_s / record.dt_s + kGridTolerance);
  if (!(first_index <= last_index)) {
    fail(record, "trim: no sample lies in [" + text_of(options.start_s) + ", " + text_of(end_s) + "] s");
  }
  const auto i0 = static_cast<std::size_t>(first_index);
  const auto i1 = std::min(static_cast<std::size_t>(last_index), record.size() - 1);
  GroundMotionRecord out = record;
  out.acceleration_m_per_s2.assign(record.acceleration_m_per_s2.begin() + static_cast<long>(i0),
                                   record.acceleration_m_per_s2.begin() + static_cast<long>(i1) + 1);
  out.processing_steps.push_back("trimmed to [" + text_of(static_cast<double>(i0) * record.dt_s) + ", " +
                                 text_of(static_cast<double>(i1) * record.dt_s) + "] s");
  return out;
}

GroundMotionRecord pad(const GroundMotionRecord& record, const PadOptions& options) {
  require_samples(record, "pad");
  const auto samples = [&](double seconds, const char* name) {
    if (!(seconds >= 0.0) || !std::isfinite(seconds) || seconds / record.dt_s > 1e9) {
      fail(record,
           std::string("pad.") + name + ": expected a time >= 0 s (at most 1e9 steps), got " + text_of(seconds));
    }
    return static_cast<std::size_t>(std::llround(seconds / record.dt_s));
  };
  const std::size_t before = samples(options.before_s, "before_s");
  const std::size_t after = samples(options.after_s, "after_s");
  GroundMotionRecord out = record;
  out.acceleration_m_per_s2.assign(before, 0.0);
  out.acceleration_m_per_s2.insert(out.acceleration_m_per_s2.end(), record.acceleration_m_per_s2.begin(),
                                   record.acceleration_m_per_s2.end());
  out.acceleration_m_per_s2.insert(out.acceleration_m_per_s2.end(), after, 0.0);
  out.processing_steps.push_back("padded with " + std::to_string(before) + " zeros before and " +
                                 std::to_string(after) + " after");
  return out;
}

GroundMotionRecord resample(const GroundMotionRecord& record, const ResampleOptions& options) {
  require_samples(record, "resample");
  const double dt_new = options.dt_s;
  if (!(dt_new > 0.0) || !std::isfinite(dt_new)) {
    fail(record, "resample.dt_s: expected a positive time step, got " + text_of(dt_new));
  }
  const double ratio = record.dt_s / dt_new;  // new samples per old step
  if (ratio < 1.0 - kGridTolerance && !options.allow_downsampling) {
    fail(record, "resample.dt_s: " + text_of(dt_new) + " s is coarser than the record's " + text_of(record.dt_s) +
                     " s; linear interpolation would alias (low-pass the "
                     "record first and set allow_downsampling)");
  }
  const auto& a = record.acceleration_m_per_s2;
  const std::size_t n = a.size();
  const double span = static_cast<double>(n - 1) * ratio;  // last old sample, in new steps
  if (span > 1e9) fail(record, "resample.dt_s: more than 1e9 samples");
  const auto n_new = static_cast<std::size_t>(std::floor(span + kGridTolerance)) + 1;

  const double rounded = std::round(ratio);
  const bool integer_ratio = rounded >= 1.0 && std::abs(ratio - rounded) <= kGridTolerance * ratio;
  const auto m = static_cast<std::size_t>(rounded);

  GroundMotionRecord out = record;
  out.dt_s = dt_new;
  out.acceleration_m_per_s2.assign(n_new, 0.0);
  for (std::size_t i = 0; i < n_new; ++i) {
    std::size_t j = 0;
    double frac = 0.0;
    if (integer_ratio) {  // exact: original samples are copied, not recomputed
      j = i / m;
      frac = static_cast<double>(i % m) / static_cast<double>(m);
    } else {
      const double x = static_cast<double>(i) / ratio;
      j = static_cast<std::size_t>(x);
      frac = x - static_cast<double>(j);
    }
    if (j + 1 >= n) {
      out.acceleration_m_per_s2[i] = a[n - 1];
    } else {
      out.acceleration_m_per_s2[i] = frac == 0.0 ? a[j] : a[j] + frac * (a[j + 1] - a[j]);
    }
  }
  out.processing_steps.push_back("resampled from dt " + text_of(record.dt_s) + " s to " + text_of(dt_new) +
                                 " s by linear interpolation");
  return out;
}

GroundMotionIntegrals velocity_and_displacement(const GroundMotionRecord& record) {
  const auto& a = record.acceleration_m_per_s2;
  const double h = record.dt_s;
  GroundMotionIntegrals out;
  out.velocity_m_per_s.assign(a.size(), 0.0);
  out.displacement_m.assign(a.size(), 0.0);
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    const double v = out.velocity_m_per_s[i];
    out.velocity_m_per_s[i + 1] = v + h * (a[i] + a[i + 1]) / 2.0;
    out.displacement_m[i + 1] = out.displacement_m[i] + h * v + h * h * (2.0 * a[i] + a[i + 1]) / 6.0;
  }
  return out;
}

GroundMotionRecord baseline_correct(const GroundMotionRecord& record, const BaselineCorrectionOptions& options) {
  require_samples(record, "baseline_correct");
  GroundMotionRecord out = record;
  auto& a = out.acceleration_m_per_s2;
  const std::size_t n = a.size();
  if (options.method == BaselineMethod::kRemoveMean) {
    double sum = 0.0;
    for (double value : a) sum += value;
    const double mean = sum / static_cast<double>(n);
    for (double& value : a) value -= mean;
    out.processing_steps.push_back("baseline: removed the mean acceleration " + text_of(mean) + " m/s^2");
    return out;
  }
  const int order = options.polynomial_order;
  if (order < 2 || order > 6) {
    fail(record, "baseline_correction.polynomial_order: expected 2..6, got " + std::to_string(order));
  }
  const auto terms = static_cast<std::size_t>(order - 1);  // t^2 .. t^order
  if (n <= terms) fail(record, "baseline_correction: too few samples for the polynomial fit");
  const double duration = record.duration_s();
  const GroundMotionIntegrals integrals = velocity_and_displacement(record);

  // Least squares in scaled time tau = t / duration in [0, 1] (well-conditioned columns),
  // by modified Gram-Schmidt with one re-orthogonalisation, in plain loops so that the
  // result does not depend on SIMD width or FMA (synthetic records use it too).
  std::vector<std::vector<double>> q(terms, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = static_cast<double>(i) * record.dt_s / duration;
    double power = tau * tau;
    for (std::size_t k = 0; k < terms; ++k) {
      q[k][i] = power;
      power *= tau;
    }
  }
  const auto dot = [n](const std::vector<double>& x, const std::vector<double>& y) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += x[i] * y[i];
    return sum;
  };
  std::vector<std::vector<double>> r(terms, std::vector<double>(terms, 0.0));
  for (std::size_t k = 0; k < terms; ++k) {
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t j = 0; j < k; ++j) {
        const double projection = dot(q[j], q[k]);
        r[j][k] += projection;
        for (std::size_t i = 0; i < n; ++i) q[k][i] -= projection * q[j][i];
      }
    }
    r[k][k] = std::sqrt(dot(q[k], q[k]));
    if (!(r[k][k] > 0.0)) fail(record, "baseline_correction: degenerate polynomial fit");
    for (std::size_t i = 0; i < n; ++i) q[k][i] /= r[k][k];
  }
  // c = R^-1 Q^T d
  std::vector<double> c(terms);
  for (std::size_t k = 0; k < terms; ++k) c[k] = dot(q[k], integrals.displacement_m);
  for (std::size_t k = terms; k-- > 0;) {
    for (std::size_t j = k + 1; j < terms; ++j) c[k] -= r[k][j] * c[j];
    c[k] /= r[k][k];
  }

  // d_fit = sum_k c_k tau^(k+2)  =>  a_fit = sum_k (k+2)(k+1) c_k tau^k / duration^2.
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = static_cast<double>(i) * record.dt_s / duration;
    double power = 1.0;
    double fit = 0.0;
    for (std::size_t k = 0; k < terms; ++k) {
      fit += static_cast<double>((k + 2) * (k + 1)) * c[k] * power;
      power *= tau;
    }
    a[i] -= fit / (duration * duration);
  }
  out.processing_steps.push_back("baseline: removed the second derivative of a degree-" + std::to_string(order) +
                                 " polynomial fitted to the displacement");
  return out;
}

}  // namespace rpsd::ground_motion
