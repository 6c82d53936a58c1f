#include "text_scan.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

#include "rpsd/ground_motion/record_error.h"

namespace rpsd::ground_motion::detail {

namespace {
constexpr std::string_view kBom = "\xEF\xBB\xBF";
}  // namespace

LineCursor::LineCursor(std::string_view text) : rest_(text), size_bytes_(text.size()) {
  if (rest_.substr(0, kBom.size()) == kBom) rest_.remove_prefix(kBom.size());
}

LineCursor::LineCursor(config::InputFile& file)
    : file_(&file), size_bytes_(static_cast<std::size_t>(file.size_bytes())) {}

bool LineCursor::next(std::string_view& line) {
  if (done_) return false;
  if (file_ != nullptr) {
    try {
      if (!file_->next_line(line_)) {
        done_ = true;
        return false;
      }
    } catch (const config::InputFileError& e) {
      throw RecordError(e.what());
    }
    line = line_;
    if (line_number_ == 0 && line.substr(0, kBom.size()) == kBom) line.remove_prefix(kBom.size());
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++line_number_;
    return true;
  }
  const auto end = rest_.find('\n');
  if (end == std::string_view::npos) {
    // The text after the last '\n' is a line only if it is not empty.
    done_ = true;
    if (rest_.empty()) return false;
    line = rest_;
    rest_ = {};
  } else {
    line = rest_.substr(0, end);
    rest_.remove_prefix(end + 1);
  }
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  ++line_number_;
  return true;
}

TokenCursor::TokenCursor(std::string_view line, std::string_view extra_separators)
    : line_(line), extra_(extra_separators) {}

bool TokenCursor::is_separator(char c) const {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || extra_.find(c) != std::string_view::npos;
}

bool TokenCursor::next(Token& token) {
  while (pos_ < line_.size() && is_separator(line_[pos_])) ++pos_;
  if (pos_ >= line_.size()) return false;
  const std::size_t start = pos_;
  while (pos_ < line_.size() && !is_separator(line_[pos_])) ++pos_;
  token.text = line_.substr(start, pos_ - start);
  token.column = start + 1;
  return true;
}

std::string quoted(std::string_view text) {
  constexpr std::size_t max_chars = 40;
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size() && i < max_chars; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
      out += static_cast<char>(c);
    } else {
      static constexpr char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xf];
    }
  }
  if (text.size() > max_chars) out += "...";
  out += '"';
  return out;
}

std::string where(std::string_view source, std::size_t line, std::size_t column) {
  std::string out(source);
  out += ':' + std::to_string(line);
  if (column > 0) out += ':' + std::to_string(column);
  out += ": ";
  return out;
}

bool parse_finite_double(std::string_view token, double& value) {
  if (token.empty()) return false;
  // from_chars takes no leading '+' and no Fortran 'D' exponent: fix both in a copy.
  if (token.front() == '+') {
    token.remove_prefix(1);
    if (token.empty() || token.front() == '-' || token.front() == '+') return false;
  }
  constexpr std::size_t max_len = 64;
  if (token.size() > max_len) return false;  // no ground-motion value needs 64 digits
  std::array<char, max_len> buffer{};
  std::copy(token.begin(), token.end(), buffer.begin());
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (buffer[i] == 'D' || buffer[i] == 'd') buffer[i] = 'E';
  }
  const char* first = buffer.data();
  const char* last = buffer.data() + token.size();
  // from_chars also accepts "inf", "nan" and hex-free forms only; reject letters other
  // than the exponent so "nan" and "infinity" are errors, not values.
  for (const char* p = first; p != last; ++p) {
    const char c = *p;
    if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'E' || c == 'e')) {
      return false;
    }
  }
  double parsed = 0.0;
  const auto result = std::from_chars(first, last, parsed, std::chars_format::general);
  if (result.ec != std::errc{} || result.ptr != last || !std::isfinite(parsed)) return false;
  value = parsed;
  return true;
}

bool parse_count(std::string_view token, std::size_t& value) {
  if (token.empty()) return false;
  if (!std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return false;
  }
  std::size_t parsed = 0;
  const auto result = std::from_chars(token.data(), token.data() + token.size(), parsed);
  if (result.ec != std::errc{} || result.ptr != token.data() + token.size()) return false;
  value = parsed;
  return true;
}

double number_or_throw(const Token& token, std::string_view source, std::size_t line, std::string_view what) {
  double value = 0.0;
  if (!parse_finite_double(token.text, value)) {
    throw RecordError(where(source, line, token.column) + "expected " + std::string(what) + ", got " +
                      quoted(token.text));
  }
  return value;
}

double converted_or_throw(double value, double factor, const Token& token, std::string_view source, std::size_t line) {
  const double converted = value * factor;
  if (!std::isfinite(converted)) {
    throw RecordError(where(source, line, token.column) +
                      "expected an acceleration value of finite size in m/s^2, got " + quoted(token.text));
  }
  return converted;
}

bool is_blank(std::string_view line) {
  TokenCursor tokens(line, "");
  Token token;
  return !tokens.next(token);
}

bool is_numeric_line(std::string_view line, std::string_view extra_separators) {
  TokenCursor tokens(line, extra_separators);
  Token token;
  bool any = false;
  double value = 0.0;
  while (tokens.next(token)) {
    if (!parse_finite_double(token.text, value)) return false;
    any = true;
  }
  return any;
}

config::InputFile open_record_file(const std::filesystem::path& file) {
  try {
    return config::InputFile(file, config::kMaxRecordFileBytes, "ground-motion record");
  } catch (const config::InputFileError& e) {
    throw RecordError(e.what());
  }
}

}  // namespace rpsd::ground_motion::detail
