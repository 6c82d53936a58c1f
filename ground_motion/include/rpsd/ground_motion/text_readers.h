// Plain-text ground-motion readers: values only (dt and unit given), and two-column
// time/acceleration files (dt inferred and its uniformity checked).
//
// Both skip blank lines and comment lines starting with '#' or '%', take blanks, ',' and
// ';' as separators, and throw RecordError "file:line[:column]: expected ..., got ..."
// for any error.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>

#include "rpsd/ground_motion/record.h"

namespace rpsd::ground_motion {

struct PlainTextOptions {
  double dt_s = 0.0;                     // required, > 0
  std::optional<AccelerationUnit> unit;  // required: the file does not say
  std::size_t skip_lines = 0;            // header lines to skip before the data
  // Unset: every value of every line, in reading order (files written 1, 5, 6 or 8 per
  // line). Set: only this 0-based column of a table; every data line then needs the
  // same number of columns as the first.
  std::optional<std::size_t> column;
  std::optional<std::size_t> expected_points;  // if set, the count must match
};

struct TimeAccelerationOptions {
  std::optional<AccelerationUnit> unit;  // required: the file does not say
  std::size_t skip_lines = 0;
  std::size_t time_column = 0;  // time in s
  std::size_t acceleration_column = 1;
  // dt = (t_last - t_first) / (n - 1); every time must lie within
  // spacing_tolerance * dt of t_first + i * dt (default: 0.1 % of a step, looser than
  // times printed with 6 significant digits, far tighter than any real irregularity).
  double spacing_tolerance = 1e-3;
};

// Not real-time safe.
GroundMotionRecord read_plain_text(const std::filesystem::path& file, const PlainTextOptions& options);
GroundMotionRecord parse_plain_text(std::string_view text, std::string_view source_name,
                                    const PlainTextOptions& options);

// The time origin moves to the first sample (sample i at t = i * dt); the file's first
// time is noted in `description`. Not real-time safe.
GroundMotionRecord read_time_acceleration(const std::filesystem::path& file, const TimeAccelerationOptions& options);
GroundMotionRecord parse_time_acceleration(std::string_view text, std::string_view source_name,
                                           const TimeAccelerationOptions& options);

}  // namespace rpsd::ground_motion
