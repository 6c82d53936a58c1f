#include "rpsd/servo/signal_converter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::servo {

namespace {
void require_converter(bool ok, const char* key, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("signal converter: ") + key + ": " + what);
}
void require_converter_non_negative(double v, const char* key) {
  require_converter(std::isfinite(v) && v >= 0.0, key, "must be a finite number, zero or positive");
}
constexpr int kMaxBits = 30;

// The converter's step and code limits, as doubles to clamp before any integer conversion (no
// converter: a zero step).
struct Codes {
  double step_v = 0.0;
  double lowest = 0.0, highest = 0.0;
};

Codes codes_of(const SignalConverterParameters& p) {
  Codes c;
  if (p.bits <= 0) return c;
  const double full_scale_v = p.full_scale_v > 0.0 ? p.full_scale_v : p.saturation_v;
  c.step_v = 2.0 * full_scale_v / std::ldexp(1.0, p.bits);
  c.highest = std::ldexp(1.0, p.bits - 1) - 1.0;
  c.lowest = -std::ldexp(1.0, p.bits - 1);
  if (p.saturation_v > 0.0) {
    // The largest step inside the saturation band, on each side.
    double inside = std::floor(p.saturation_v / c.step_v);
    while (inside > 0.0 && inside * c.step_v > p.saturation_v) inside -= 1.0;
    c.highest = std::min(c.highest, inside);
    c.lowest = std::max(c.lowest, -inside);
  }
  return c;
}
}  // namespace

void SignalConverterParameters::validate() const {
  require_converter_non_negative(units_per_volt, "units_per_volt");
  require_converter_non_negative(noise_rms_v, "noise_rms_v");
  require_converter_non_negative(saturation_v, "saturation_v");
  require_converter_non_negative(full_scale_v, "full_scale_v");
  require_converter(bits >= 0 && bits <= kMaxBits, "bits", "must be from 0 to 30");
  require_converter(bits > 0 || full_scale_v == 0.0, "full_scale_v", "set without bits");
  require_converter(bits == 0 || full_scale_v > 0.0 || saturation_v > 0.0, "bits",
                    "a converter needs full_scale_v or saturation_v");
  if (units_per_volt == 0.0) {
    // Without a scale there are no volts for the other stages to act on.
    require_converter(noise_rms_v == 0.0, "noise_rms_v", "needs units_per_volt");
    require_converter(saturation_v == 0.0, "saturation_v", "needs units_per_volt");
    require_converter(bits == 0, "bits", "needs units_per_volt");
  }
}

ConverterRange SignalConverterParameters::range() const {
  ConverterRange r;
  if (units_per_volt == 0.0) return r;
  // The same arithmetic as convert(), so that a clamped reading equals its rail exactly.
  if (const Codes c = codes_of(*this); c.step_v > 0.0) {
    r.low = c.lowest * c.step_v * units_per_volt;
    r.high = c.highest * c.step_v * units_per_volt;
  } else if (saturation_v > 0.0) {
    r.low = -saturation_v * units_per_volt;
    r.high = saturation_v * units_per_volt;
  }
  return r;
}

SignalConverter::SignalConverter(const SignalConverterParameters& parameters)
    : parameters_(parameters), generator_(parameters.seed) {
  parameters_.validate();
  const Codes c = codes_of(parameters_);
  step_v_ = c.step_v;
  lowest_code_ = c.lowest;
  highest_code_ = c.highest;
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
