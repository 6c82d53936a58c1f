// How many equal substeps cover an interval with none longer than the plant's step
// (internal). The count is checked before the cast to int: a period of 1e300 s, from a rate
// no reader should have let through, must be an error rather than undefined behaviour.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::servo::detail {

// More substeps than this in one interval is a caller's mistake (1 s at a 1 MHz plant
// rate is 1e6).
inline constexpr double kMaxSubsteps = 1e7;

// `steps`: the interval over the plant's step (need not be whole).
inline int substeps(double steps) {
  const double count = std::ceil(steps - 1e-9);
  if (!(count <= kMaxSubsteps)) {
    throw std::invalid_argument("a plant interval of " + std::to_string(steps) + " plant steps exceeds 1e7");
  }
  return std::max(1, static_cast<int>(count));
}

}  // namespace rpsd::servo::detail
