#include "rpsd/ground_motion/text_readers.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "rpsd/ground_motion/record_error.h"
#include "text_scan.h"

namespace rpsd::ground_motion {
namespace {

using detail::where;

constexpr std::string_view kSeparators = ",;";

bool is_comment_or_blank(std::string_view line) {
  const auto first = line.find_first_not_of(" \t\r\v\f");
  return first == std::string_view::npos || line[first] == '#' || line[first] == '%';
}

AccelerationUnit required_unit(const std::optional<AccelerationUnit>& unit, const std::string& source) {
  if (!unit) {
    throw RecordError(source +
                      ": the acceleration units must be declared (g, m/s^2 or cm/s^2): "
                      "a plain-text record does not state them");
  }
  return *unit;
}

// Skips `count` header lines; the file must have them.
void skip_header(detail::LineCursor& lines, std::size_t count, const std::string& source) {
  std::string_view line;
  for (std::size_t i = 0; i < count; ++i) {
    if (!lines.next(line)) {
      throw RecordError(where(source, lines.line_number() + 1) + "expected " + std::to_string(count) +
                        " header lines (skip_lines), the file has " + std::to_string(lines.line_number()));
    }
  }
}

std::string format_seconds(double t) {
  std::ostringstream out;
  out.precision(10);
  out << t;
  return out.str();
}

GroundMotionRecord plain_text_lines(detail::LineCursor& lines, const std::string& source,
                                    const PlainTextOptions& options) {
  if (!(options.dt_s > 0.0) || !std::isfinite(options.dt_s)) {
    throw RecordError(source +
                      ": expected dt_s, a positive number of seconds, for a plain-text "
                      "record, got " +
                      format_seconds(options.dt_s));
  }
  GroundMotionRecord record;
  record.source = source;
  record.format = RecordFormat::kPlainText;
  record.original_unit = required_unit(options.unit, source);
  record.dt_s = options.dt_s;
  const double factor = to_m_per_s2(record.original_unit);

  skip_header(lines, options.skip_lines, source);
  std::string_view line;
  std::size_t columns = 0;
  std::size_t columns_line = 0;
  std::vector<detail::Token> row;
  while (lines.next(line)) {
    if (is_comment_or_blank(line)) continue;
    detail::TokenCursor tokens(line, kSeparators);
    detail::Token token;
    if (!options.column) {
      while (tokens.next(token)) {
        const double value = detail::number_or_throw(token, source, lines.line_number(),
                                                     "an acceleration value (set skip_lines to skip header lines)");
        record.acceleration_m_per_s2.push_back(
            detail::converted_or_throw(value, factor, token, source, lines.line_number()));
      }
      continue;
    }
    row.clear();
    while (tokens.next(token)) row.push_back(token);
    if (columns == 0) {
      columns = row.size();
      columns_line = lines.line_number();
      if (columns <= *options.column) {
        throw RecordError(where(source, lines.line_number()) + "expected at least " +
                          std::to_string(*options.column + 1) + " columns (column " + std::to_string(*options.column) +
                          ", 0-based, was asked for), got " + std::to_string(columns));
      }
    } else if (row.size() != columns) {
      throw RecordError(where(source, lines.line_number()) + "expected " + std::to_string(columns) +
                        " columns like line " + std::to_string(columns_line) + ", got " + std::to_string(row.size()));
    }
    for (const auto& t : row) {  // every cell must be a number, not only the chosen one
      detail::number_or_throw(t, source, lines.line_number(), "a number (set skip_lines to skip header lines)");
    }
    const auto& cell = row[*options.column];
    record.acceleration_m_per_s2.push_back(
        detail::converted_or_throw(detail::number_or_throw(cell, source, lines.line_number(), "a number"), factor, cell,
                                   source, lines.line_number()));
  }
  const std::size_t last_line = std::max<std::size_t>(lines.line_number(), 1);
  if (record.acceleration_m_per_s2.empty()) {
    throw RecordError(where(source, last_line) + "expected acceleration values, got none (empty file?)");
  }
  if (options.expected_points && record.acceleration_m_per_s2.size() != *options.expected_points) {
    throw RecordError(where(source, last_line) + "expected " + std::to_string(*options.expected_points) +
                      " values, got " + std::to_string(record.acceleration_m_per_s2.size()) +
                      " by the end of the file");
  }
  return record;
}

GroundMotionRecord time_acceleration_lines(detail::LineCursor& lines, const std::string& source,
                                           const TimeAccelerationOptions& options) {
  if (!(options.spacing_tolerance >= 0.0 && options.spacing_tolerance < 0.5)) {
    throw RecordError(source + ": expected spacing_tolerance in [0, 0.5) (a fraction of dt), got " +
                      format_seconds(options.spacing_tolerance));
  }
  if (options.time_column == options.acceleration_column) {
    throw RecordError(source + ": the time and acceleration columns must differ (both are " +
                      std::to_string(options.time_column) + ")");
  }
  GroundMotionRecord record;
  record.source = source;
  record.format = RecordFormat::kTimeAcceleration;
  record.original_unit = required_unit(options.unit, source);
  const double factor = to_m_per_s2(record.original_unit);
  const std::size_t needed = std::max(options.time_column, options.acceleration_column) + 1;

  skip_header(lines, options.skip_lines, source);
  std::vector<double> times;
  std::vector<std::size_t> line_numbers;
  std::vector<detail::Token> row;
  std::string_view line;
  while (lines.next(line)) {
    if (is_comment_or_blank(line)) continue;
    detail::TokenCursor tokens(line, kSeparators);
    detail::Token token;
    row.clear();
    while (tokens.next(token)) row.push_back(token);
    if (row.size() < needed) {
      throw RecordError(where(source, lines.line_number()) + "expected at least " + std::to_string(needed) +
                        " columns (time in column " + std::to_string(options.time_column) +
                        ", acceleration in column " + std::to_string(options.acceleration_column) + "), got " +
                        std::to_string(row.size()));
    }
    const double t = detail::number_or_throw(row[options.time_column], source, lines.line_number(),
                                             "a time in s (set skip_lines to skip header lines)");
    const double a =
        detail::number_or_throw(row[options.acceleration_column], source, lines.line_number(), "an acceleration value");
    if (!times.empty() && !(t > times.back())) {
      throw RecordError(where(source, lines.line_number(), row[options.time_column].column) +
                        "expected a time greater than " + format_seconds(times.back()) + " s (line " +
                        std::to_string(line_numbers.back()) + "), got " +
                        detail::quoted(row[options.time_column].text));
    }
    times.push_back(t);
    line_numbers.push_back(lines.line_number());
    record.acceleration_m_per_s2.push_back(
        detail::converted_or_throw(a, factor, row[options.acceleration_column], source, lines.line_number()));
  }
  if (times.size() < 2) {
    throw RecordError(where(source, std::max<std::size_t>(lines.line_number(), 1)) +
                      "expected at least two time/acceleration rows to infer dt, got " + std::to_string(times.size()));
  }
  const std::size_t n = times.size();
  const double t0 = times.front();
  const double dt = (times.back() - t0) / static_cast<double>(n - 1);
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw RecordError(where(source, line_numbers.back()) + "cannot infer a positive time step");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double expected = t0 + static_cast<double>(i) * dt;
    const double off = std::abs(times[i] - expected);
    if (off > options.spacing_tolerance * dt) {
      throw RecordError(where(source, line_numbers[i]) + "expected the uniform time " + format_seconds(expected) +
                        " s (dt = " + format_seconds(dt) + " s inferred from the first and last rows) within " +
                        format_seconds(options.spacing_tolerance) + " dt, got " + format_seconds(times[i]) +
                        " s; resample the file or raise "
                        "spacing_tolerance");
    }
  }
  record.dt_s = dt;
  if (t0 != 0.0) record.description = "time column starts at " + format_seconds(t0) + " s";
  return record;
}

}  // namespace

GroundMotionRecord parse_plain_text(std::string_view text, std::string_view source_name,
                                    const PlainTextOptions& options) {
  detail::LineCursor lines(text);
  return plain_text_lines(lines, std::string(source_name), options);
}

GroundMotionRecord parse_time_acceleration(std::string_view text, std::string_view source_name,
                                           const TimeAccelerationOptions& options) {
  detail::LineCursor lines(text);
  return time_acceleration_lines(lines, std::string(source_name), options);
}

GroundMotionRecord read_plain_text(const std::filesystem::path& file, const PlainTextOptions& options) {
  config::InputFile input = detail::open_record_file(file);
  detail::LineCursor lines(input);
  return plain_text_lines(lines, file.string(), options);
}

GroundMotionRecord read_time_acceleration(const std::filesystem::path& file, const TimeAccelerationOptions& options) {
  config::InputFile input = detail::open_record_file(file);
  detail::LineCursor lines(input);
  return time_acceleration_lines(lines, file.string(), options);
}

}  // namespace rpsd::ground_motion
