// The coordinator's own limits for one actuator channel (specimen scale): a second layer
// beside the servo node's, and the rules that tell a run-away. A command beyond its stroke or
// increment is never sent; a measured force beyond its bound, or a tracking error beyond its
// bound, stops the test at once. Every limit defaults to the rig's envelope (within_envelope).
#pragma once

#include <limits>
#include <string>

#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/envelope.h"

namespace rpsd::coordinator {

struct CoordinatorLimits {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double max_stroke_m = kNone;     // |command|
  double max_increment_m = kNone;  // |command change| per control period
  // The same limit stated per second, so that it means the same at any control rate: give it
  // or max_increment_m, not both; within_envelope makes max_increment_m this times the period.
  double max_velocity_m_per_s = kNone;
  double max_force_n = kNone;           // |measured force|
  double max_tracking_error_m = kNone;  // |target - measured|: beyond it the test has run away
};

// The limits of a channel on a rig: a limit left out (infinite) becomes the envelope's (the
// stroke, the force capacity, the velocity capacity over one control period, and half the
// stroke of tracking error); a limit beyond the envelope is refused with
// std::invalid_argument naming the key. A max_velocity_m_per_s given becomes max_increment_m at
// control_period_s (and is kept, for reports); both given are refused. Not real-time safe.
CoordinatorLimits within_envelope(CoordinatorLimits limits, const servo::Envelope& envelope, double control_period_s);

// The limits of what has no rig of its own (a DOF an experimental setup drives: its rig is its
// actuators'): only a limit stated per second becomes max_increment_m at control_period_s (and
// is kept, for reports); both given are refused (config::KeyError on max_velocity_m_per_s).
// Nothing else is defaulted. Not real-time safe.
CoordinatorLimits per_control_period(CoordinatorLimits limits, double control_period_s);

// The limits as within_envelope made them (`stated`: as the file gave them) must lie strictly
// inside what the channel's converters can read: max_stroke_m inside the displacement's A/D,
// max_force_n inside the force's. Otherwise std::invalid_argument "max_force_n: ..." naming
// converters_key's converter too (servo::require_readable). Not real-time safe.
void require_readable(const CoordinatorLimits& stated, const CoordinatorLimits& effective,
                      const servo::ReadingRanges& ranges, const std::string& converters_key);

}  // namespace rpsd::coordinator
