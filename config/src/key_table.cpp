#include "rpsd/config/key_table.h"

#include "rpsd/config/kind_list.h"

#include <cmath>
#include <cstdio>

namespace rpsd::config {

std::string number_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string range_text(const Number& spec) {
  const bool low = std::isfinite(spec.min), high = std::isfinite(spec.max);
  if (low && high) {
    if (!spec.min_open && !spec.max_open) return number_text(spec.min) + " to " + number_text(spec.max);
    return (spec.min_open ? "> " : ">= ") + number_text(spec.min) + " and " + (spec.max_open ? "< " : "<= ") +
           number_text(spec.max);
  }
  if (low) return (spec.min_open ? "> " : ">= ") + number_text(spec.min);
  if (high) return (spec.max_open ? "< " : "<= ") + number_text(spec.max);
  return "any";
}

namespace {

// A value the reader will accept: the lower bound, nudged inside an open one, or 1.
double inside(const Number& spec) {
  if (spec.admits(1.0)) return 1.0;
  if (std::isfinite(spec.min) && std::isfinite(spec.max)) return 0.5 * (spec.min + spec.max);
  if (std::isfinite(spec.min)) return spec.min_open ? spec.min + 1.0 : spec.min;
  return spec.max_open ? spec.max - 1.0 : spec.max;
}

}  // namespace

KeyTable::KeyTable(std::string path, std::shared_ptr<std::vector<KeyRow>> rows)
    : path_(std::move(path)), rows_(rows ? std::move(rows) : std::make_shared<std::vector<KeyRow>>()) {}

std::string KeyTable::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void KeyTable::add(std::string_view key, std::string type, std::string_view unit, std::string fallback,
                   std::string range, std::string_view meaning) {
  rows_->push_back(
      {path_of(key), std::move(type), std::string(unit), std::move(fallback), std::move(range), std::string(meaning)});
}

double KeyTable::number(std::string_view key, const Number& spec) {
  add(key, "number", spec.unit, "", range_text(spec), spec.meaning);
  return inside(spec);
}

double KeyTable::number_or(std::string_view key, double fallback, const Number& spec) {
  add(key, "number", spec.unit, number_text(fallback), range_text(spec), spec.meaning);
  return fallback;
}

std::vector<double> KeyTable::numbers(std::string_view key, const Number& spec, std::size_t max_count) {
  add(key, "list of 1 to " + std::to_string(max_count) + " numbers", spec.unit, "", range_text(spec), spec.meaning);
  return {inside(spec)};
}

long KeyTable::whole_number(std::string_view key, long min, long max, std::string_view meaning) {
  add(key, "whole number", "", "", std::to_string(min) + " to " + std::to_string(max), meaning);
  return max;  // a count as large as it may be: a list sized by it shows its longest
}

long KeyTable::whole_number_or(std::string_view key, long min, long max, long fallback, std::string_view meaning) {
  add(key, "whole number", "", std::to_string(fallback), std::to_string(min) + " to " + std::to_string(max), meaning);
  return fallback;
}

bool KeyTable::boolean_or(std::string_view key, bool fallback, std::string_view meaning) {
  add(key, "true or false", "", fallback ? "true" : "false", "", meaning);
  return fallback;
}

std::string KeyTable::choice(std::string_view key, const std::vector<std::string_view>& choices,
                             std::string_view meaning) {
  add(key, "one of", "", "", listed(choices), meaning);
  return choices.empty() ? std::string() : std::string(choices.front());
}

std::string KeyTable::text(std::string_view key, std::string_view meaning) {
  add(key, "text", "", "", "", meaning);
  return "text";
}

std::optional<double> KeyTable::optional_number(std::string_view key, const Number& spec) {
  add(key, "number", spec.unit, "none", range_text(spec), spec.meaning);
  return std::nullopt;
}

std::optional<std::string> KeyTable::optional_text(std::string_view key, std::string_view meaning) {
  add(key, "text", "", "none", "", meaning);
  return std::nullopt;
}

std::optional<std::vector<double>> KeyTable::optional_numbers(std::string_view key, const Number& spec,
                                                              std::size_t max_count) {
  add(key, "list of 1 to " + std::to_string(max_count) + " numbers", spec.unit, "none", range_text(spec), spec.meaning);
  return std::nullopt;
}

std::optional<std::vector<std::string>> KeyTable::optional_texts(std::string_view key, std::string_view meaning,
                                                                 std::size_t max_count) {
  add(key, "list of 1 to " + std::to_string(max_count) + " texts", "", "none", "", meaning);
  return std::nullopt;
}

std::unique_ptr<Source> KeyTable::optional_section(std::string_view key, std::string_view meaning) {
  add(key, "section", "", "none", "", meaning);
  return std::make_unique<KeyTable>(path_of(key), rows_);
}

std::string KeyTable::choice_or(std::string_view key, const std::vector<std::string_view>& choices,
                                std::string_view fallback, std::string_view meaning) {
  add(key, "one of", "", std::string(fallback), listed(choices), meaning);
  return std::string(fallback);
}

std::vector<std::vector<double>> KeyTable::matrix(std::string_view key, const Number& entry, std::size_t max_rows) {
  add(key, "matrix: rows, a diagonal or one number, at most " + std::to_string(max_rows) + " rows", entry.unit, "",
      "diagonal " + range_text(entry) + ", others within +/- " + number_text(entry.max), entry.meaning);
  return {{inside(entry)}};
}

std::vector<std::unique_ptr<Source>> KeyTable::sections(std::string_view key, std::size_t max_count,
                                                        std::string_view meaning) {
  add(key, "list of 1 to " + std::to_string(max_count) + " sections", "", "", "", meaning);
  std::vector<std::unique_ptr<Source>> one;
  one.push_back(std::make_unique<KeyTable>(path_of(key) + "[]", rows_));
  return one;
}

bool KeyTable::has(std::string_view) { return false; }

std::unique_ptr<Source> KeyTable::section(std::string_view key, std::string_view meaning) {
  add(key, "section", "", "", "", meaning);
  return std::make_unique<KeyTable>(path_of(key), rows_);
}

std::unique_ptr<Source> KeyTable::file(std::string_view key, std::string_view meaning) {
  add(key, "file", "", "", "", meaning);
  return std::make_unique<KeyTable>(path_of(key) + " (file)", rows_);
}

std::filesystem::path KeyTable::relative_file(std::string_view key, std::string_view meaning) {
  add(key, "file name", "", "", "", meaning);
  return "file";
}

std::optional<std::filesystem::path> KeyTable::optional_relative_file(std::string_view key, std::string_view meaning) {
  add(key, "file name", "", "none", "", meaning);
  return std::nullopt;
}

void KeyTable::fail(std::string_view key, const std::string& message) {
  throw ListingStopped("a reader failed while its keys were being listed: " + path_of(key) + ": " + message);
}

void KeyTable::fail_section(const std::string& message) {
  throw ListingStopped("a reader failed while its keys were being listed: " +
                       (path_.empty() ? std::string("(document)") : path_) + ": " + message);
}

}  // namespace rpsd::config
