// The coordinator's own limits for one actuator channel (specimen scale): a second layer
// beside the servo node's. A command beyond its stroke or increment is never sent; a
// measured force beyond its bound stops the test at once. Infinity: not checked.
#pragma once

#include <limits>

namespace rpsd::coordinator {

struct CoordinatorLimits {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double max_stroke_m = kNone;     // |command|
  double max_increment_m = kNone;  // |command change| per control period
  double max_force_n = kNone;      // |measured force|
};

}  // namespace rpsd::coordinator
