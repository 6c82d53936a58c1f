// What the kinds' readers share (private to setups/): lengths and coordinates with their
// ranges, a list of an exact length, a side, and the check that PlanarSetup accepts the
// geometry read, reported at a key of the section.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/setups/setup_kinds.h"

namespace rpsd::setups::reading {

// A rig's dimensions: up to 100 m.
inline constexpr double kMaxDimensionM = 100.0;

inline config::Number length(std::string_view meaning) { return {"m", meaning, 0.0, kMaxDimensionM, true}; }
inline config::Number distance(std::string_view meaning) {
  return config::Number::between(0.0, kMaxDimensionM, "m", meaning);
}
inline config::Number coordinate(std::string_view meaning) {
  return config::Number::between(-kMaxDimensionM, kMaxDimensionM, "m", meaning);
}

ActuatorSide read_side(config::Source& section, std::string_view key, std::string_view meaning);

// Fails at `key` unless `values` has exactly `count` entries. Call after every key is read (a
// listing gives lists of one).
void require_count(config::Source& section, std::string_view key, const std::vector<double>& values, std::size_t count);

// Fails at `key` with PlanarSetup's own message when it refuses `g`.
void require_valid(config::Source& section, std::string_view key, const PlanarGeometry& g);

// An actuator's name as records and messages use it: letters, digits, '_' and '-'.
bool is_plain_name(std::string_view name) noexcept;

}  // namespace rpsd::setups::reading
