// A ground-acceleration record: uniformly sampled, SI units, sample i at t = i * dt_s.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rpsd::ground_motion {

// Standard gravity (exact by definition, CGPM 1901); "g" in a record means this.
inline constexpr double kStandardGravityMPerS2 = 9.80665;

// Units an acceleration record is written in. Records are stored in m/s² whatever they
// were written in; `original_unit` remembers the file's unit.
enum class AccelerationUnit { kG, kMPerS2, kCmPerS2 };

// Factor that turns a value in `unit` into m/s² (g → 9.80665, cm/s² → 0.01).
double to_m_per_s2(AccelerationUnit unit);

// "g", "m/s^2", "cm/s^2".
std::string_view unit_name(AccelerationUnit unit);

// Where a record came from.
enum class RecordFormat {
  kPeerAt2Old,        // PEER AT2, line 4 "NPTS=  4096, DT= .01000 SEC"
  kPeerAt2NgaWest1,   // PEER AT2, line 4 "4000    0.0100    NPTS, DT"
  kPeerAt2NgaWest2,   // PEER AT2, line 4 "NPTS=   5590, DT=   .0050 SEC," (trailing comma)
  kPlainText,         // values only, dt and unit given by the caller
  kTimeAcceleration,  // two columns t, a (dt inferred)
  kSynthetic,         // generate_synthetic_ground_motion()
};

std::string_view format_name(RecordFormat format);

struct GroundMotionRecord {
  std::string source;                     // file path (as given) or a generator name, used in messages
  std::string description;                // AT2: event, date, station, component (line 2); else free text
  std::vector<std::string> header_lines;  // AT2: the four header lines as read
  // Processing applied since reading, in order, e.g. "scaled by 0.4"; the format and
  // original unit keep describing where the samples came from.
  std::vector<std::string> processing_steps;
  RecordFormat format = RecordFormat::kPlainText;
  AccelerationUnit original_unit = AccelerationUnit::kMPerS2;
  double dt_s = 0.0;
  std::vector<double> acceleration_m_per_s2;

  std::size_t size() const { return acceleration_m_per_s2.size(); }
  // Time of the last sample, (n - 1) * dt_s; 0 for fewer than two samples.
  double duration_s() const;
};

// The sample of largest magnitude (first one on ties); its value keeps its sign.
struct PeakGroundAcceleration {
  double value_m_per_s2 = 0.0;
  std::size_t index = 0;
  double time_s = 0.0;
};

// Throws std::invalid_argument for an empty record. Not real-time safe.
PeakGroundAcceleration peak_ground_acceleration(const GroundMotionRecord& record);

// Ground acceleration at time t_s by linear interpolation between samples (the same
// piecewise-linear signal the response spectra and resample() assume); 0 before the
// first and after the last sample. Real-time safe (no allocation, no throw).
double acceleration_at(const GroundMotionRecord& record, double t_s) noexcept;

}  // namespace rpsd::ground_motion
