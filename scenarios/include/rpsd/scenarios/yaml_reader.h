// Strict, located reading of YAML mappings into typed structs. Every value is read through
// a MappingReader, which knows the file and the key path; finish() rejects keys nobody read,
// so a misspelt key is an error rather than a silent default. Not real-time safe.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rpsd/scenarios/config_error.h"

namespace rpsd::scenarios {

/// Parses a YAML file; syntax errors become ConfigError with the file's line and column.
YAML::Node load_yaml_file(const std::filesystem::path& file);

/// Parses YAML text; `name` stands for the file in messages.
YAML::Node parse_yaml_text(const std::string& text, const std::string& name);

class MappingReader {
 public:
  /// `node` must be a mapping; `key_path` is its dotted path ("" for the document root).
  MappingReader(YAML::Node node, std::string file, std::string key_path);

  double number(const std::string& key);
  double positive_number(const std::string& key);
  double non_negative_number(const std::string& key);
  double number_or(const std::string& key, double fallback);
  double positive_number_or(const std::string& key, double fallback);
  double non_negative_number_or(const std::string& key, double fallback);
  bool boolean_or(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::optional<std::string> optional_string(const std::string& key);
  std::vector<double> positive_numbers(const std::string& key);
  /// A non-empty list of finite numbers.
  std::vector<double> numbers(const std::string& key);
  /// A non-empty list of equally long, non-empty lists of finite numbers (matrix rows).
  std::vector<std::vector<double>> number_rows(const std::string& key);
  /// A whole number in [minimum, maximum].
  long whole_number(const std::string& key, long minimum, long maximum);
  long whole_number_or(const std::string& key, long minimum, long maximum, long fallback);
  /// A non-empty list of mappings, each read with its own path `key[i]`.
  std::vector<MappingReader> mappings(const std::string& key);
  MappingReader mapping(const std::string& key);
  std::optional<MappingReader> optional_mapping(const std::string& key);
  /// Whether the key is present; the key counts as known to finish() either way.
  bool has(const std::string& key);

  /// Rejects every key that was not read. Call after reading all known keys.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  const std::string& file() const { return file_; }
  std::string path_of(const std::string& key) const;

 private:
  YAML::Node required(const std::string& key);
  double parse_number(const YAML::Node& value, const std::string& key) const;
  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& path, const std::string& message) const;

  YAML::Node node_;
  std::string file_;
  std::string key_path_;
  std::set<std::string> read_keys_;
};

}  // namespace rpsd::scenarios
