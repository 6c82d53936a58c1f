#include "rpsd/ground_motion/record.h"

#include <cmath>
#include <stdexcept>

namespace rpsd::ground_motion {

double to_m_per_s2(AccelerationUnit unit) {
  switch (unit) {
    case AccelerationUnit::kG:
      return kStandardGravityMPerS2;
    case AccelerationUnit::kMPerS2:
      return 1.0;
    case AccelerationUnit::kCmPerS2:
      return 0.01;
  }
  throw std::invalid_argument("unknown acceleration unit");
}

std::string_view unit_name(AccelerationUnit unit) {
  switch (unit) {
    case AccelerationUnit::kG:
      return "g";
    case AccelerationUnit::kMPerS2:
      return "m/s^2";
    case AccelerationUnit::kCmPerS2:
      return "cm/s^2";
  }
  return "?";
}

std::string_view format_name(RecordFormat format) {
  switch (format) {
    case RecordFormat::kPeerAt2Old:
      return "PEER AT2 (old PEER header)";
    case RecordFormat::kPeerAt2NgaWest1:
      return "PEER AT2 (NGA-West1 header)";
    case RecordFormat::kPeerAt2NgaWest2:
      return "PEER AT2 (NGA-West2 header)";
    case RecordFormat::kPlainText:
      return "plain text";
    case RecordFormat::kTimeAcceleration:
      return "time/acceleration columns";
    case RecordFormat::kSynthetic:
      return "synthetic";
  }
  return "?";
}

double GroundMotionRecord::duration_s() const {
  return acceleration_m_per_s2.size() < 2 ? 0.0 : static_cast<double>(acceleration_m_per_s2.size() - 1) * dt_s;
}

PeakGroundAcceleration peak_ground_acceleration(const GroundMotionRecord& record) {
  if (record.acceleration_m_per_s2.empty()) {
    throw std::invalid_argument(record.source + ": empty record has no peak acceleration");
  }
  PeakGroundAcceleration peak;
  double largest = -1.0;
  for (std::size_t i = 0; i < record.acceleration_m_per_s2.size(); ++i) {
    const double a = record.acceleration_m_per_s2[i];
    if (std::abs(a) > largest) {
      largest = std::abs(a);
      peak.value_m_per_s2 = a;
      peak.index = i;
    }
  }
  peak.time_s = static_cast<double>(peak.index) * record.dt_s;
  return peak;
}

double acceleration_at(const GroundMotionRecord& record, double t_s) noexcept {
  const auto& a = record.acceleration_m_per_s2;
  if (a.empty() || !(record.dt_s > 0.0) || !(t_s >= 0.0)) return 0.0;
  const double x = t_s / record.dt_s;
  const double last = static_cast<double>(a.size() - 1);
  if (x > last) return 0.0;
  const auto i = static_cast<std::size_t>(x);
  if (i + 1 >= a.size()) return a.back();
  const double frac = x - static_cast<double>(i);
  return a[i] + frac * (a[i + 1] - a[i]);
}

}  // namespace rpsd::ground_motion
