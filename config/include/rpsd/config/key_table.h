// A Source that reads nothing and writes down every key asked for: the table of a section's
// keys (path, type, unit, default, range, meaning) for the scenario reference. Numbers come
// back as their default or as a value inside their range (whole numbers as their largest), so
// that a reader runs through;
// optional numbers and texts come back absent, optional sections present.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/config/source.h"

namespace rpsd::config {

// What KeyTable::fail throws: the reader found the listing's values do not fit together,
// after it had read its keys.
class ListingStopped : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

struct KeyRow {
  std::string path;  // "compensation.delay_s"
  // "number", "whole number", "list of numbers", "true or false", "one of ...", "section",
  // "file" (another file, its keys listed), "file name" (a file another reader opens)
  std::string type;
  std::string unit;
  std::string fallback;  // the default, empty when the key is required
  std::string range;
  std::string meaning;
};

class KeyTable final : public Source {
 public:
  explicit KeyTable(std::string path = {}, std::shared_ptr<std::vector<KeyRow>> rows = nullptr);

  const std::vector<KeyRow>& rows() const { return *rows_; }

  double number(std::string_view key, const Number& spec) override;
  double number_or(std::string_view key, double fallback, const Number& spec) override;
  std::vector<double> numbers(std::string_view key, const Number& spec, std::size_t max_count) override;
  long whole_number(std::string_view key, long min, long max, std::string_view meaning) override;
  long whole_number_or(std::string_view key, long min, long max, long fallback, std::string_view meaning) override;
  bool boolean_or(std::string_view key, bool fallback, std::string_view meaning) override;
  std::string text(std::string_view key, std::string_view meaning) override;
  std::string choice(std::string_view key, const std::vector<std::string_view>& choices,
                     std::string_view meaning) override;
  std::optional<double> optional_number(std::string_view key, const Number& spec) override;
  std::optional<std::string> optional_text(std::string_view key, std::string_view meaning) override;
  std::optional<std::vector<double>> optional_numbers(std::string_view key, const Number& spec,
                                                      std::size_t max_count) override;
  std::optional<std::vector<std::string>> optional_texts(std::string_view key, std::string_view meaning,
                                                         std::size_t max_count) override;
  std::unique_ptr<Source> optional_section(std::string_view key, std::string_view meaning) override;
  std::string choice_or(std::string_view key, const std::vector<std::string_view>& choices, std::string_view fallback,
                        std::string_view meaning) override;
  std::vector<std::vector<double>> matrix(std::string_view key, const Number& entry, std::size_t max_rows) override;
  std::vector<std::unique_ptr<Source>> sections(std::string_view key, std::size_t max_count,
                                                std::string_view meaning) override;
  bool has(std::string_view key) override;
  std::unique_ptr<Source> section(std::string_view key, std::string_view meaning) override;
  std::unique_ptr<Source> file(std::string_view key, std::string_view meaning) override;
  std::filesystem::path relative_file(std::string_view key, std::string_view meaning) override;
  std::optional<std::filesystem::path> optional_relative_file(std::string_view key, std::string_view meaning) override;
  void finish() override {}
  [[noreturn]] void fail(std::string_view key, const std::string& message) override;
  [[noreturn]] void fail_section(const std::string& message) override;

 private:
  std::string path_of(std::string_view key) const;
  void add(std::string_view key, std::string type, std::string_view unit, std::string fallback, std::string range,
           std::string_view meaning);

  std::string path_;
  std::shared_ptr<std::vector<KeyRow>> rows_;
};

// The text of a number as the reference prints it ("0.001", "1e+30", "inf").
std::string number_text(double v);
// "> 0", "0 to 1", ">= 1", "any"
std::string range_text(const Number& spec);

}  // namespace rpsd::config
