#include "rpsd/coordinator/coordinator_limits.h"

#include "rpsd/config/key_error.h"

namespace rpsd::coordinator {

CoordinatorLimits within_envelope(CoordinatorLimits limits, const servo::Envelope& envelope, double control_period_s) {
  servo::tighten_to_rig(limits.max_stroke_m, envelope.stroke_m, "max_stroke_m", "stroke");
  servo::tighten_to_rig(limits.max_force_n, envelope.force_n, "max_force_n", "force capacity");
  if (limits.max_velocity_m_per_s != CoordinatorLimits::kNone) {
    if (limits.max_increment_m != CoordinatorLimits::kNone) {
      throw config::KeyError(
          "max_velocity_m_per_s",
          "give max_increment_m (per control period) or max_velocity_m_per_s (per second), not both");
    }
    servo::tighten_to_rig(limits.max_velocity_m_per_s, envelope.velocity_m_per_s, "max_velocity_m_per_s",
                          "velocity capacity");
    limits.max_increment_m = limits.max_velocity_m_per_s * control_period_s;
  }
  servo::tighten_to_rig(limits.max_increment_m, envelope.velocity_m_per_s * control_period_s, "max_increment_m",
                        "velocity capacity over one control period");
  if (limits.max_tracking_error_m == CoordinatorLimits::kNone) limits.max_tracking_error_m = 0.5 * envelope.stroke_m;
  return limits;
}

CoordinatorLimits per_control_period(CoordinatorLimits limits, double control_period_s) {
  if (limits.max_velocity_m_per_s == CoordinatorLimits::kNone) return limits;
  if (limits.max_increment_m != CoordinatorLimits::kNone) {
    throw config::KeyError("max_velocity_m_per_s",
                           "give max_increment_m (per control period) or max_velocity_m_per_s (per second), not both");
  }
  limits.max_increment_m = limits.max_velocity_m_per_s * control_period_s;
  return limits;
}

void require_readable(const CoordinatorLimits& stated, const CoordinatorLimits& effective,
                      const servo::ReadingRanges& ranges, const std::string& converters_key) {
  servo::require_readable(effective.max_stroke_m, stated.max_stroke_m == CoordinatorLimits::kNone,
                          ranges.displacement_m, "max_stroke_m", converters_key + ".displacement", "m");
  servo::require_readable(effective.max_force_n, stated.max_force_n == CoordinatorLimits::kNone, ranges.force_n,
                          "max_force_n", converters_key + ".force", "N");
}

}  // namespace rpsd::coordinator
