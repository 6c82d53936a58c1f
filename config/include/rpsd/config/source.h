// How a module states, and reads, the keys of one section of a configuration file without
// knowing the file's format: every key is read with its unit, its allowed range, its
// default and one line of meaning. scenarios/ reads YAML files through it, and the scenario
// reference (docs/scenario-reference.md) is written from the very same calls, so the two
// cannot disagree. Not real-time safe.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rpsd::config {

// A real number's unit, range and meaning. The range is closed unless a bound is marked open.
struct Number {
  std::string_view unit;  // SI, as in the key's name ("s", "m", "N/m"); empty: none
  std::string_view meaning;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static Number positive(std::string_view unit, std::string_view meaning) { return {unit, meaning, 0.0, kInf, true}; }
  static Number non_negative(std::string_view unit, std::string_view meaning) { return {unit, meaning, 0.0, kInf}; }
  static Number any(std::string_view unit, std::string_view meaning) { return {unit, meaning}; }
  static Number between(double low, double high, std::string_view unit, std::string_view meaning) {
    return {unit, meaning, low, high};
  }
  bool admits(double v) const { return (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max); }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
};

// One section (a mapping of keys) of a file.
class Source {
 public:
  virtual ~Source() = default;

  virtual double number(std::string_view key, const Number& spec) = 0;
  virtual double number_or(std::string_view key, double fallback, const Number& spec) = 0;
  // A non-empty list of at most max_count numbers, each within the spec; a longer list is
  // refused before its items are read.
  virtual std::vector<double> numbers(std::string_view key, const Number& spec, std::size_t max_count) = 0;
  virtual long whole_number(std::string_view key, long min, long max, std::string_view meaning) = 0;
  virtual long whole_number_or(std::string_view key, long min, long max, long fallback, std::string_view meaning) = 0;
  virtual bool boolean_or(std::string_view key, bool fallback, std::string_view meaning) = 0;
  // A word or a name (free text).
  virtual std::string text(std::string_view key, std::string_view meaning) = 0;
  // One of `choices`; anything else is an error that lists them.
  virtual std::string choice(std::string_view key, const std::vector<std::string_view>& choices,
                             std::string_view meaning) = 0;
  // A number, a text or a section the file may leave out (then nullopt, nullptr). A listing
  // (KeyTable) lists the key and returns nothing for a number or a text, and a section to
  // descend into.
  virtual std::optional<double> optional_number(std::string_view key, const Number& spec) = 0;
  virtual std::optional<std::string> optional_text(std::string_view key, std::string_view meaning) = 0;
  virtual std::optional<std::vector<double>> optional_numbers(std::string_view key, const Number& spec,
                                                              std::size_t max_count) = 0;
  // A non-empty list of at most max_count texts (words, names, addresses), or nullopt.
  virtual std::optional<std::vector<std::string>> optional_texts(std::string_view key, std::string_view meaning,
                                                                 std::size_t max_count) = 0;
  virtual std::unique_ptr<Source> optional_section(std::string_view key, std::string_view meaning) = 0;
  // One of `choices`, or `fallback` when the key is left out.
  virtual std::string choice_or(std::string_view key, const std::vector<std::string_view>& choices,
                                std::string_view fallback, std::string_view meaning) = 0;
  // A square matrix given as rows, as a list (its diagonal) or as one number (1 x 1), of at
  // most max_rows rows; the entries of the diagonal within `entry`, the others within
  // -entry.max to entry.max. Returned as rows.
  virtual std::vector<std::vector<double>> matrix(std::string_view key, const Number& entry, std::size_t max_rows) = 0;
  // A non-empty list of at most max_count sections (a listing gives one).
  virtual std::vector<std::unique_ptr<Source>> sections(std::string_view key, std::size_t max_count,
                                                        std::string_view meaning) = 0;
  // Whether the key is given (it counts as known to finish() either way). A listing says no:
  // prefer the optional_* reads, which it lists.
  virtual bool has(std::string_view key) = 0;
  // A nested section, and a section that is the root of another file named by the key
  // (relative to this file).
  virtual std::unique_ptr<Source> section(std::string_view key, std::string_view meaning) = 0;
  virtual std::unique_ptr<Source> file(std::string_view key, std::string_view meaning) = 0;
  // The name of a file another reader opens (a record, a matrix), relative to this file's
  // folder or absolute: its absolute path. A reader of a document writes the absolute path
  // back into it, so that the document emitted after reading runs from any folder.
  virtual std::filesystem::path relative_file(std::string_view key, std::string_view meaning) = 0;
  virtual std::optional<std::filesystem::path> optional_relative_file(std::string_view key,
                                                                      std::string_view meaning) = 0;
  // Rejects every key that was not read.
  virtual void finish() = 0;
  // An error at the key, with the file's location and the key's path; and one about the
  // section as a whole (values that do not fit together). A listing throws
  // ListingStopped: a reader checks its values after reading its keys, so that a listing
  // that stops there has listed them all.
  [[noreturn]] virtual void fail(std::string_view key, const std::string& message) = 0;
  [[noreturn]] virtual void fail_section(const std::string& message) = 0;
};

}  // namespace rpsd::config
