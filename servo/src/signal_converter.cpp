#include "rpsd/servo/signal_converter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::servo {

namespace {
void require(bool ok, const char* key, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("signal converter: ") + key + ": " + what);
}
void require_non_negative(double v, const char* key) {
  require(std::isfinite(v) && v >= 0.0, key, "must be a finite number, zero or positive");
}
constexpr int kMaxBits = 30;
}  // namespace

void SignalConverterParameters::validate() const {
  require_non_negative(units_per_volt, "units_per_volt");
  require_non_negative(noise_rms_v, "noise_rms_v");
  require_non_negative(saturation_v, "saturation_v");
  require_non_negative(full_scale_v, "full_scale_v");
  require(bits >= 0 && bits <= kMaxBits, "bits", "must be from 0 to 30");
  require(bits > 0 || full_scale_v == 0.0, "full_scale_v", "set without bits");
  require(bits == 0 || full_scale_v > 0.0 || saturation_v > 0.0, "bits",
          "a converter needs full_scale_v or saturation_v");
  if (units_per_volt == 0.0) {
    // Without a scale there are no volts for the other stages to act on.
    require(noise_rms_v == 0.0, "noise_rms_v", "needs units_per_volt");
    require(saturation_v == 0.0, "saturation_v", "needs units_per_volt");
    require(bits == 0, "bits", "needs units_per_volt");
  }
}

SignalConverter::SignalConverter(const SignalConverterParameters& parameters)
    : parameters_(parameters), generator_(parameters.seed) {
  parameters_.validate();
  if (parameters_.bits > 0) {
    const double full_scale_v = parameters_.full_scale_v > 0.0 ? parameters_.full_scale_v : parameters_.saturation_v;
    step_v_ = 2.0 * full_scale_v / std::ldexp(1.0, parameters_.bits);
    highest_code_ = std::ldexp(1.0, parameters_.bits - 1) - 1.0;
    lowest_code_ = -std::ldexp(1.0, parameters_.bits - 1);
    if (parameters_.saturation_v > 0.0) {
      // The largest step inside the saturation band, on each side.
      double inside = std::floor(parameters_.saturation_v / step_v_);
      while (inside > 0.0 && inside * step_v_ > parameters_.saturation_v) inside -= 1.0;
      highest_code_ = std::min(highest_code_, inside);
      lowest_code_ = std::max(lowest_code_, -inside);
    }
  }
}

void SignalConverter::reseed() {
  generator_.seed(parameters_.seed);
  normal_.reset();  // drops the second value of a pair it may hold
}

double SignalConverter::convert(double physical) {
  saturated_ = false;
  const SignalConverterParameters& p = parameters_;
  if (p.units_per_volt == 0.0) return physical;
  const double noise_v = p.noise_rms_v > 0.0 ? p.noise_rms_v * normal_(generator_) : 0.0;
  if (!std::isfinite(physical)) return physical;

  double v = physical / p.units_per_volt + noise_v;
  if (p.saturation_v > 0.0) {
    if (v > p.saturation_v) {
      v = p.saturation_v;
      saturated_ = true;
    } else if (v < -p.saturation_v) {
      v = -p.saturation_v;
      saturated_ = true;
    }
  }
  if (step_v_ > 0.0) {
    double code = std::round(v / step_v_);  // halves away from zero, symmetric about 0 V
    if (code > highest_code_) {
      code = highest_code_;
      saturated_ = true;
    } else if (code < lowest_code_) {
      code = lowest_code_;
      saturated_ = true;
    }
    v = code * step_v_;
  }
  return v * p.units_per_volt;
}

}  // namespace rpsd::servo
