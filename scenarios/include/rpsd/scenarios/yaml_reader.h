// Strict, located reading of YAML mappings into typed structs. Every value is read through
// a MappingReader, which knows the file and the key path; finish() rejects keys nobody read,
// so a misspelt key is an error rather than a silent default. Not real-time safe.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/scenarios/config_error.h"

namespace rpsd::scenarios {

// Parses a YAML file; syntax errors become ConfigError with the file's line and column.
YAML::Node load_yaml_file(const std::filesystem::path& file);

// Parses YAML text; `name` stands for the file in messages.
YAML::Node parse_yaml_text(const std::string& text, const std::string& name);

class MappingReader final : public config::Source {
 public:
  // `node` must be a mapping; `key_path` is its dotted path ("" for the document root).
  MappingReader(YAML::Node node, std::string file, std::string key_path);

  double number(std::string_view key);
  double positive_number(std::string_view key);
  double non_negative_number(std::string_view key);
  double number_or(std::string_view key, double fallback);
  double positive_number_or(std::string_view key, double fallback);
  double non_negative_number_or(std::string_view key, double fallback);
  bool boolean_or(std::string_view key, bool fallback);
  std::string string(std::string_view key);
  std::optional<std::string> optional_string(std::string_view key);
  std::vector<double> positive_numbers(std::string_view key);
  // A non-empty list of finite numbers.
  std::vector<double> numbers(std::string_view key);
  // A non-empty list of equally long, non-empty lists of finite numbers (matrix rows).
  std::vector<std::vector<double>> number_rows(std::string_view key);
  // A whole number in [minimum, maximum].
  long whole_number(std::string_view key, long minimum, long maximum);
  long whole_number_or(std::string_view key, long minimum, long maximum, long fallback);
  // A non-empty list of mappings, each read with its own path `key[i]`.
  std::vector<MappingReader> mappings(std::string_view key);
  MappingReader mapping(std::string_view key);
  std::optional<MappingReader> optional_mapping(std::string_view key);

  // Rejects every key that was not read. Call after reading all known keys.
  void finish() const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  // config::Source: the same reads, stated with their unit, range and meaning.
  double number(std::string_view key, const config::Number& spec) override;
  double number_or(std::string_view key, double fallback, const config::Number& spec) override;
  std::vector<double> numbers(std::string_view key, const config::Number& spec) override;
  long whole_number(std::string_view key, long minimum, long maximum, std::string_view meaning) override;
  long whole_number_or(std::string_view key, long minimum, long maximum, long fallback,
                       std::string_view meaning) override;
  bool boolean_or(std::string_view key, bool fallback, std::string_view meaning) override;
  std::string text(std::string_view key, std::string_view meaning) override {
    (void)meaning;
    return string(key);
  }
  std::string choice(std::string_view key, const std::vector<std::string_view>& choices,
                     std::string_view meaning) override;
  bool has(std::string_view key) override;
  std::unique_ptr<config::Source> section(std::string_view key, std::string_view meaning) override;
  std::unique_ptr<config::Source> file(std::string_view key, std::string_view meaning) override;
  void finish() override { static_cast<const MappingReader*>(this)->finish(); }
  [[noreturn]] void fail(std::string_view key, const std::string& message) override {
    static_cast<const MappingReader*>(this)->fail(key, message);
  }
  [[noreturn]] void fail_section(const std::string& message) override { fail_at(node_, key_path_, message); }
  const std::string& file() const { return file_; }
  std::string path_of(std::string_view key) const;

 private:
  YAML::Node required(std::string_view key);
  double checked(double value, std::string_view key, const config::Number& spec) const;
  double parse_number(const YAML::Node& value, std::string_view key) const;
  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& path, const std::string& message) const;

  YAML::Node node_;
  std::string file_;
  std::string key_path_;
  std::set<std::string> read_keys_;
};

}  // namespace rpsd::scenarios
