// Line and number scanning shared by the ground-motion readers (internal). Locale-free
// (std::from_chars), no regex, every failure a RecordError naming source:line[:column].
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "rpsd/config/input_file.h"

namespace rpsd::ground_motion::detail {

// Splits text, or a file as it is read, into lines ('\n', with a trailing '\r' dropped);
// skips a UTF-8 BOM. A line taken from a file stays valid until the next call.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text);
  explicit LineCursor(config::InputFile& file);
  // Next line into `line`; false at the end. Line numbers start at 1.
  bool next(std::string_view& line);
  std::size_t line_number() const { return line_number_; }
  // The bytes of the whole text or file (a bound for reserving, never trusted from a header).
  std::size_t size_bytes() const { return size_bytes_; }

 private:
  std::string_view rest_;
  config::InputFile* file_ = nullptr;
  std::string line_;
  bool done_ = false;
  std::size_t line_number_ = 0;
  std::size_t size_bytes_ = 0;
};

// One token of a line: its text and 1-based column.
struct Token {
  std::string_view text;
  std::size_t column = 0;
};

// Iterates over the tokens of one line, separated by whitespace and by any character
// of `extra_separators` (e.g. "," for CSV files).
class TokenCursor {
 public:
  TokenCursor(std::string_view line, std::string_view extra_separators);
  bool next(Token& token);

 private:
  bool is_separator(char c) const;
  std::string_view line_;
  std::string_view extra_;
  std::size_t pos_ = 0;
};

// The token quoted for a message, cut at 40 characters, non-printable bytes as \xNN.
std::string quoted(std::string_view text);

// "source:line: " or "source:line:column: " (column 0 leaves it out).
std::string where(std::string_view source, std::size_t line, std::size_t column = 0);

// Parses a whole token as a finite double: optional sign, Fortran 'D' exponents
// accepted. False for anything else (partial number, inf, nan, out of range).
bool parse_finite_double(std::string_view token, double& value);

// Parses a whole token as an unsigned decimal integer (digits only, no overflow).
bool parse_count(std::string_view token, std::size_t& value);

// Parses `token` as a finite double or throws RecordError
// "source:line:column: expected <what>, got "token"".
double number_or_throw(const Token& token, std::string_view source, std::size_t line, std::string_view what);

// value * factor (a unit conversion), or RecordError at the token when that overflows.
double converted_or_throw(double value, double factor, const Token& token, std::string_view source, std::size_t line);

// True when the line holds only separators (no token).
bool is_blank(std::string_view line);

// True when every token of the line is a number (used to recognise a missing header).
bool is_numeric_line(std::string_view line, std::string_view extra_separators);

// Opens a record file: a regular file of at most config::kMaxRecordFileBytes, else a
// RecordError naming it.
config::InputFile open_record_file(const std::filesystem::path& file);

}  // namespace rpsd::ground_motion::detail
