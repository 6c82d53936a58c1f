// What a lab's electronics do to one signal between the physical quantity and the controller:
// a sensor or actuator scale, electrical noise, saturation and an n-bit A/D or D/A converter.
// The stages run in this order, each optional:
//   physical / units_per_volt -> + Gaussian noise (volts) -> clamp to +/- saturation_v
//   -> round to the nearest converter step (mid-tread: 0 V is a code) -> * units_per_volt.
// The noise is electrical, so it is added in volts before the converter sees the signal. The
// converter has two's-complement codes k = -2^(bits-1) .. 2^(bits-1) - 1 of step
// q = 2 full_scale_v / 2^bits, and k is further limited to |k q| <= saturation_v, so a
// quantised value never leaves the saturation band: a clamped input reads the largest step
// inside it (q (2^(bits-1) - 1) at the top when full_scale_v equals saturation_v).
// A non-finite input comes out unchanged, never clamped into a finite value, so that the safety
// checks downstream see it.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace rpsd::servo {

// What a converter can put out, in physical units: its rails, the lowest and highest values it
// gives (infinite without saturation or converter). A reading at a rail may stand for any value
// beyond it, so a limit on a reading must lie strictly inside (docs/safety.md).
struct ConverterRange {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();

  bool bounded() const { return std::isfinite(low) || std::isfinite(high); }
  // The reading sits on a rail (a finite one): the true value may be anywhere beyond it.
  bool at_rail(double reading) const {
    return (std::isfinite(high) && reading >= high) || (std::isfinite(low) && reading <= low);
  }
  // +/- magnitude reads without touching either rail.
  bool represents(double magnitude) const { return magnitude < high && -magnitude > low; }
  // The smaller of the two rails' magnitudes.
  double rail_magnitude() const { return std::fmin(high, -low); }
};

struct SignalConverterParameters {
  // Sensor or actuator scale, e.g. 7.89e-3 m/V or 1096 N/V; 0: no voltage stages, the signal passes unchanged.
  double units_per_volt = 0.0;
  double noise_rms_v = 0.0;   // Gaussian noise, RMS volts (0: none)
  double saturation_v = 0.0;  // clamp to +/- this many volts (0: none)
  int bits = 0;               // converter resolution, at most 30 (0: no converter)
  double full_scale_v = 0.0;  // converter range +/- volts; 0: saturation_v's
  std::uint64_t seed = 0;     // noise generator seed

  // Throws std::invalid_argument naming the key: a negative or non-finite value, bits above 30,
  // bits without a full scale or saturation, full_scale_v without bits, a voltage stage without
  // units_per_volt.
  void validate() const;
  // The rails of a converter of these (valid) parameters: exactly the values convert() gives
  // when it clamps, and the largest and smallest it can give at all.
  ConverterRange range() const;
};

class SignalConverter {
 public:
  // Validates the parameters. Not real-time safe.
  explicit SignalConverter(const SignalConverterParameters& parameters);

  // The physical value as the controller sees it (or as the actuator receives it). Draws one
  // noise sample per call whatever the input. Real-time safe: no allocation, locks or exceptions.
  double convert(double physical);

  // Restarts the noise sequence from the seed, so that a reset run repeats exactly. Real-time safe.
  void reseed();

  // One converter step in physical units (0 without a converter).
  double step_units() const { return step_v_ * parameters_.units_per_volt; }
  // The last conversion was clamped, by the saturation or by the converter's range.
  bool saturated() const { return saturated_; }
  const SignalConverterParameters& parameters() const { return parameters_; }

 private:
  SignalConverterParameters parameters_;
  double step_v_ = 0.0;       // converter step q in volts
  double lowest_code_ = 0.0;  // code limits, as doubles to clamp before any integer conversion
  double highest_code_ = 0.0;
  bool saturated_ = false;
  std::mt19937_64 generator_;
  std::normal_distribution<double> normal_{0.0, 1.0};  // scaled by noise_rms_v
};

}  // namespace rpsd::servo
