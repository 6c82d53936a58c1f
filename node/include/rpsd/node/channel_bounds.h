// One channel's limits as a tick uses them: the products and flags that depend only on the
// node's config and control period, worked out once when the controller is built instead of on
// every tick. Each figure is the same expression, in the same order, as the tick computed
// before, so each comparison and each command is the same to the last bit.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "rpsd/node/servo_node_config.h"

namespace rpsd::node {

struct ChannelBounds {
  double stroke_m = 0.0;               // max_stroke_m
  double velocity_step_m = 0.0;        // max_velocity_m_per_s * period: the velocity limit as a change
  double increment_m = 0.0;            // max_increment_m
  double acceleration_m_per_s2 = 0.0;  // max_acceleration_m_per_s2
  double force_n = 0.0;                // max_force_n
  double max_speed_m_per_s = 0.0;      // the velocity and increment limits' speed, the lower
  bool follow_accelerates = false;     // a finite acceleration limit clamps the command
  double follow_step_m_per_s = 0.0;    // max_acceleration_m_per_s2 * period
  bool stop_brakes = false;            // a finite stop deceleration clamps and brakes
  double stop_step_m_per_s = 0.0;      // stop_deceleration_m_per_s2 * period
  double stop_quarter_step2 = 0.0;     // (stop step)^2 / 4, of braking_speed
  double stop_twice_m_per_s2 = 0.0;    // 2 stop_deceleration_m_per_s2, of braking_speed
  double stop_half_step = 0.0;         // stop step / 2, of braking_speed
  bool force_guard = false;            // a guard stiffness > 0 and a finite force limit
  double guard_stiffness_n_per_m = 0.0;

  // Readings strictly between these are neither on a converter's rail nor at the rig's capacity
  // (check_measurement looks closer at any other, a NaN too).
  double quiet_low_m = 0.0, quiet_high_m = 0.0, quiet_low_n = 0.0, quiet_high_n = 0.0;

  static ChannelBounds of(const ChannelLimits& l, double period_s) {
    ChannelBounds b;
    b.stroke_m = l.max_stroke_m;
    b.velocity_step_m = l.max_velocity_m_per_s * period_s;
    b.increment_m = l.max_increment_m;
    b.acceleration_m_per_s2 = l.max_acceleration_m_per_s2;
    b.force_n = l.max_force_n;
    b.max_speed_m_per_s = std::min(l.max_velocity_m_per_s, l.max_increment_m / period_s);
    b.follow_accelerates = std::isfinite(l.max_acceleration_m_per_s2);
    b.follow_step_m_per_s = l.max_acceleration_m_per_s2 * period_s;
    b.stop_brakes = std::isfinite(l.stop_deceleration_m_per_s2);
    b.stop_step_m_per_s = l.stop_deceleration_m_per_s2 * period_s;
    b.stop_quarter_step2 = b.stop_step_m_per_s * b.stop_step_m_per_s / 4.0;
    b.stop_twice_m_per_s2 = 2.0 * l.stop_deceleration_m_per_s2;
    b.stop_half_step = b.stop_step_m_per_s / 2.0;
    b.force_guard = l.force_guard_stiffness_n_per_m > 0.0 && std::isfinite(l.max_force_n);
    b.guard_stiffness_n_per_m = l.force_guard_stiffness_n_per_m;
    return b;
  }

  // A reading r with low < r < high is on no rail of `rail` (at_rail: r >= a finite high or
  // r <= a finite low) and not beyond the rig (|r| >= rig).
  static void quiet_between(const servo::ConverterRange& rail, double rig, double& low, double& high) {
    high = std::min(std::isfinite(rail.high) ? rail.high : std::numeric_limits<double>::infinity(), rig);
    low = std::max(std::isfinite(rail.low) ? rail.low : -std::numeric_limits<double>::infinity(), -rig);
  }
  void read_within(const servo::Envelope& rig, const servo::ReadingRanges& rails) {
    quiet_between(rails.displacement_m, rig.stroke_m, quiet_low_m, quiet_high_m);
    quiet_between(rails.force_n, rig.force_n, quiet_low_n, quiet_high_n);
  }
  bool quiet(double displacement_m, double force_n) const {
    return displacement_m > quiet_low_m && displacement_m < quiet_high_m && force_n > quiet_low_n &&
           force_n < quiet_high_n;
  }

  // The fastest command velocity that can still stop within `distance` at the stop
  // deceleration, one control period at a time (at once when it is infinite).
  double braking_speed(double distance, double period_s) const {
    if (distance <= 0.0) return 0.0;
    if (!stop_brakes) return distance / period_s;
    return std::min(distance / period_s,
                    std::sqrt(stop_quarter_step2 + stop_twice_m_per_s2 * distance) - stop_half_step);
  }
};

}  // namespace rpsd::node
