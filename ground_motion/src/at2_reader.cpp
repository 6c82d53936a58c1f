#include "rpsd/ground_motion/at2_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>
#include <utility>
#include <vector>

#include "rpsd/ground_motion/record_error.h"
#include "text_scan.h"

namespace rpsd::ground_motion {
namespace {

using detail::where;

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\v\f");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\v\f");
  return std::string(text.substr(first, last - first + 1));
}

constexpr std::string_view kLine4Forms =
    "\"NPTS=<n>, DT=<dt> SEC\" (old PEER, NGA-West2) or \"<n> <dt> NPTS, DT\" (NGA-West1)";

// Line 3: the quantity must be acceleration; the word after "UNITS" (skipping OF/ARE/IN
// and punctuation) names the unit.
std::optional<AccelerationUnit> units_of_line3(std::string_view line, std::string_view source,
                                               std::size_t line_number) {
  const std::string text = upper(line);
  const bool acceleration = text.find("ACCEL") != std::string::npos;
  if (!acceleration && (text.find("VELOC") != std::string::npos || text.find("DISPL") != std::string::npos)) {
    throw RecordError(where(source, line_number) +
                      "expected an acceleration time history, got a velocity or displacement "
                      "header " +
                      detail::quoted(line));
  }
  const auto at = text.find("UNITS");
  if (at == std::string::npos) return std::nullopt;
  std::size_t p = at + 5;
  const auto skip_filler = [&] {
    bool moved = true;
    while (moved) {
      moved = false;
      while (p < text.size() &&
             (text[p] == ' ' || text[p] == '\t' || text[p] == '(' || text[p] == ':' || text[p] == '=')) {
        ++p;
        moved = true;
      }
      for (std::string_view word : {"OF ", "ARE ", "IN "}) {
        if (text.compare(p, word.size(), word) == 0) {
          p += word.size();
          moved = true;
        }
      }
    }
  };
  skip_filler();
  std::size_t end = p;
  while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '/' ||
                               text[end] == '^' || text[end] == '*')) {
    ++end;
  }
  const std::string unit = text.substr(p, end - p);
  static constexpr std::array<std::string_view, 1> g_names = {"G"};
  static constexpr std::array<std::string_view, 10> cm_names = {
      "CM/S/S", "CM/S^2", "CM/S2", "CM/S**2", "CM/SEC/SEC", "CM/SEC^2", "CM/SEC2", "CM/SEC**2", "GAL", "GALS"};
  static constexpr std::array<std::string_view, 8> m_names = {"M/S/S",     "M/S^2",   "M/S2",   "M/S**2",
                                                              "M/SEC/SEC", "M/SEC^2", "M/SEC2", "M/SEC**2"};
  const auto in = [&](const auto& names) { return std::find(names.begin(), names.end(), unit) != names.end(); };
  if (in(g_names)) return AccelerationUnit::kG;
  if (in(cm_names)) return AccelerationUnit::kCmPerS2;
  if (in(m_names)) return AccelerationUnit::kMPerS2;
  throw RecordError(where(source, line_number, p + 1) + "expected the units after UNITS (G, CM/S/S or M/S/S), got " +
                    detail::quoted(line.substr(std::min(p, line.size()))));
}

struct Line4 {
  std::size_t npts = 0;
  double dt_s = 0.0;
  RecordFormat format = RecordFormat::kPeerAt2Old;
};

// A character cursor over the upper-cased line 4 that throws with the column.
class Line4Parser {
 public:
  Line4Parser(std::string_view original, std::string_view source, std::size_t line_number)
      : original_(original), text_(upper(original)), source_(source), line_(line_number) {}

  Line4 parse() {
    skip_blanks();
    Line4 out;
    std::size_t npts_column = 0;
    std::string npts_token;
    std::size_t dt_column = 0;
    std::string dt_token;
    if (keyword("NPTS")) {
      // NPTS=  4096, DT= .01000 SEC   and   NPTS=   5590, DT=   .0050 SEC,
      expect('=');
      npts_column = p_ + 1;
      npts_token = take_while_digits();
      optional(',');
      if (!keyword("DT")) fail("\"DT\"");
      expect('=');
      dt_column = p_ + 1;
      dt_token = take_number_chars();
      skip_blanks();
      if (!keyword("SEC")) keyword("S");
      if (optional(',')) out.format = RecordFormat::kPeerAt2NgaWest2;
    } else if (p_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[p_]))) {
      // 4000    0.0100    NPTS, DT
      npts_column = p_ + 1;
      npts_token = take_while_digits();
      if (p_ < text_.size() && text_[p_] != ' ' && text_[p_] != '\t') fail("a blank after NPTS");
      skip_blanks();
      dt_column = p_ + 1;
      dt_token = take_number_chars();
      if (!keyword("NPTS")) fail("\"NPTS, DT\" after the two numbers");
      optional(',');
      if (!keyword("DT")) fail("\"DT\" after \"NPTS,\"");
      out.format = RecordFormat::kPeerAt2NgaWest1;
    } else {
      fail("the point count and time step");
    }
    skip_blanks();
    if (p_ != text_.size()) fail("the end of the line");

    if (!detail::parse_count(npts_token, out.npts) || out.npts == 0) {
      throw RecordError(where(source_, line_, npts_column) + "expected NPTS as a positive whole number, got " +
                        detail::quoted(npts_token));
    }
    if (!detail::parse_finite_double(dt_token, out.dt_s) || !(out.dt_s > 0.0)) {
      throw RecordError(where(source_, line_, dt_column) + "expected DT as a positive number of seconds, got " +
                        detail::quoted(dt_token));
    }
    return out;
  }

 private:
  [[noreturn]] void fail(std::string_view what) const {
    throw RecordError(where(source_, line_, p_ + 1) + "expected " + std::string(what) +
                      " in the NPTS/DT line, one of " + std::string(kLine4Forms) + ", got " +
                      detail::quoted(original_));
  }
  void skip_blanks() {
    while (p_ < text_.size() && (text_[p_] == ' ' || text_[p_] == '\t')) ++p_;
  }
  bool keyword(std::string_view word) {
    skip_blanks();
    if (text_.compare(p_, word.size(), word) != 0) return false;
    p_ += word.size();
    return true;
  }
  void expect(char c) {
    skip_blanks();
    if (p_ >= text_.size() || text_[p_] != c) fail(std::string("'") + c + "'");
    ++p_;
  }
  bool optional(char c) {
    skip_blanks();
    if (p_ < text_.size() && text_[p_] == c) {
      ++p_;
      return true;
    }
    return false;
  }
  std::string take_while_digits() {
    skip_blanks();
    const std::size_t start = p_;
    while (p_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[p_]))) ++p_;
    if (p_ == start) fail("a whole number (NPTS)");
    return text_.substr(start, p_ - start);
  }
  std::string take_number_chars() {
    skip_blanks();
    const std::size_t start = p_;
    while (p_ < text_.size()) {
      const char c = text_[p_];
      const bool exponent_sign = (c == '+' || c == '-') && p_ > start && (text_[p_ - 1] == 'E' || text_[p_ - 1] == 'D');
      const bool ok =
          std::isdigit(static_cast<unsigned char>(c)) || c == '.' || ((c == '+' || c == '-') && p_ == start) ||
          exponent_sign ||
          ((c == 'E' || c == 'D') && p_ > start && p_ + 1 < text_.size() &&
           (std::isdigit(static_cast<unsigned char>(text_[p_ + 1])) || text_[p_ + 1] == '+' || text_[p_ + 1] == '-'));
      if (!ok) break;
      ++p_;
    }
    if (p_ == start) fail("a number (DT)");
    return text_.substr(start, p_ - start);
  }

  std::string_view original_;
  std::string text_;
  std::string_view source_;
  std::size_t line_;
  std::size_t p_ = 0;
};

// The reader proper, over lines from text or from a file as it is read.
GroundMotionRecord parse_lines(detail::LineCursor& lines, const std::string& source, const At2ReadOptions& options) {
  // Copies: a line from a file lives only until the next one is read.
  std::array<std::string, 4> header{};
  std::size_t header_count = 0;
  std::string_view line;
  while (header_count < header.size() && lines.next(line)) header[header_count++] = line;

  const bool blank = std::all_of(header.begin(), header.begin() + static_cast<std::ptrdiff_t>(header_count),
                                 [](const std::string& h) { return detail::is_blank(h); });
  if (header_count == 0 || blank) {
    throw RecordError(where(source, 1) + (header_count == 0 ? "empty file" : "blank header lines") +
                      "; expected a PEER AT2 header (banner, event, units, NPTS/DT) "
                      "followed by the acceleration values");
  }
  if (detail::is_numeric_line(header[0], "")) {
    throw RecordError(where(source, 1) +
                      "expected the 4-line PEER AT2 header (banner, event, units, NPTS/DT), "
                      "got numbers: the header is missing");
  }
  if (header_count < header.size()) {
    throw RecordError(where(source, header_count) + "the file ends after " + std::to_string(header_count) +
                      " header lines; expected 4 (banner, event, units, NPTS/DT) and the values");
  }

  GroundMotionRecord record;
  record.source = source;
  record.description = trimmed(header[1]);
  for (const auto& h : header) {
    std::string kept(h);
    kept.erase(kept.find_last_not_of(" \t\r\v\f") + 1);
    record.header_lines.push_back(std::move(kept));
  }

  const auto declared = units_of_line3(header[2], source, 3);
  if (!declared && !options.unit_if_unstated) {
    throw RecordError(where(source, 3) +
                      "expected the units on line 3 (e.g. \"ACCELERATION TIME HISTORY IN UNITS "
                      "OF G\"), got " +
                      detail::quoted(header[2]));
  }
  record.original_unit = declared ? *declared : *options.unit_if_unstated;

  const Line4 line4 = Line4Parser(header[3], source, 4).parse();
  record.format = line4.format;
  record.dt_s = line4.dt_s;

  // Never trust NPTS for the allocation: each value takes at least two bytes.
  record.acceleration_m_per_s2.reserve(std::min(line4.npts, lines.size_bytes() / 2 + 1));
  const double factor = to_m_per_s2(record.original_unit);
  std::size_t last_line_with_values = 4;
  while (lines.next(line)) {
    detail::TokenCursor tokens(line, "");
    detail::Token token;
    while (tokens.next(token)) {
      if (record.acceleration_m_per_s2.size() == line4.npts) {
        throw RecordError(where(source, lines.line_number(), token.column) +
                          "expected the end of the data after NPTS=" + std::to_string(line4.npts) +
                          " values (line 4), got one more value " + detail::quoted(token.text));
      }
      const double value = detail::number_or_throw(token, source, lines.line_number(),
                                                   "an acceleration value (value " +
                                                       std::to_string(record.acceleration_m_per_s2.size() + 1) +
                                                       " of NPTS=" + std::to_string(line4.npts) + ")");
      record.acceleration_m_per_s2.push_back(
          detail::converted_or_throw(value, factor, token, source, lines.line_number()));
      last_line_with_values = lines.line_number();
    }
  }
  if (record.acceleration_m_per_s2.size() != line4.npts) {
    throw RecordError(where(source, std::max(lines.line_number(), last_line_with_values)) +
                      "expected NPTS=" + std::to_string(line4.npts) + " values (line 4), got only " +
                      std::to_string(record.acceleration_m_per_s2.size()) + " before the end of the file (truncated?)");
  }
  return record;
}

}  // namespace

GroundMotionRecord parse_peer_at2(std::string_view text, std::string_view source_name, const At2ReadOptions& options) {
  detail::LineCursor lines(text);
  return parse_lines(lines, std::string(source_name), options);
}

GroundMotionRecord read_peer_at2(const std::filesystem::path& file, const At2ReadOptions& options) {
  config::InputFile input = detail::open_record_file(file);
  detail::LineCursor lines(input);
  return parse_lines(lines, file.string(), options);
}

}  // namespace rpsd::ground_motion
