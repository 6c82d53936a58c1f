// Strict, located reading of YAML mappings into typed structs. Every value is read through
// a MappingReader, which knows the file and the key path; finish() rejects keys nobody read,
// so a misspelt key is an error rather than a silent default. Not real-time safe.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/scenarios/config_error.h"

namespace rpsd::scenarios {

// The longest list a file may give (a longer one is refused before its items are read).
inline constexpr std::size_t kMaxListItems = 10'000;

// Reads a YAML file's text: a regular file of at most config::kMaxYamlFileBytes, else a
// ConfigError naming it.
std::string read_yaml_file_text(const std::filesystem::path& file);

// Parses a YAML file; syntax errors become ConfigError with the file's line and column.
YAML::Node load_yaml_file(const std::filesystem::path& file);

// Parses YAML text; `name` stands for the file in messages.
YAML::Node parse_yaml_text(const std::string& text, const std::string& name);

// While `log` is set (a test's; nullptr: none), every key a MappingReader accepts goes into it
// as its path with list indices left out ("experimental[].dof"): how a test checks that the
// scenario reference lists every key the readers accept. Not thread-safe.
void log_accepted_keys(std::set<std::string>* log);

// A value the command line put into the document (--set #2, --record): an error in it names
// the override, not a line of the file it never was in.
struct OverrideNode {
  YAML::Node value;
  std::string origin;  // "--set #2 (servo.delay_s=-1)"
};
using OverrideNodes = std::shared_ptr<const std::vector<OverrideNode>>;

// Every read goes through config::Source, with its range and meaning, so that the scenario
// reference lists it.
class MappingReader final : public config::Source {
 public:
  // `node` must be a mapping; `key_path` is its dotted path ("" for the document root).
  MappingReader(YAML::Node node, std::string file, std::string key_path, OverrideNodes overrides = nullptr);

  // Rejects every key that was not read. Call after reading all known keys.
  void finish() const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  // config::Source: every read states its unit, range and meaning.
  double number(std::string_view key, const config::Number& spec) override;
  double number_or(std::string_view key, double fallback, const config::Number& spec) override;
  std::vector<double> numbers(std::string_view key, const config::Number& spec, std::size_t max_count) override;
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
  std::optional<double> optional_number(std::string_view key, const config::Number& spec) override;
  std::optional<std::string> optional_text(std::string_view key, std::string_view meaning) override;
  std::optional<std::vector<double>> optional_numbers(std::string_view key, const config::Number& spec,
                                                      std::size_t max_count) override;
  std::optional<std::vector<std::string>> optional_texts(std::string_view key, std::string_view meaning,
                                                         std::size_t max_count) override;
  std::unique_ptr<config::Source> optional_section(std::string_view key, std::string_view meaning) override;
  std::string choice_or(std::string_view key, const std::vector<std::string_view>& choices, std::string_view fallback,
                        std::string_view meaning) override;
  std::vector<std::vector<double>> matrix(std::string_view key, const config::Number& entry,
                                          std::size_t max_rows) override;
  std::vector<std::unique_ptr<config::Source>> sections(std::string_view key, std::size_t max_count,
                                                        std::string_view meaning) override;
  bool has(std::string_view key) override;
  std::unique_ptr<config::Source> section(std::string_view key, std::string_view meaning) override;
  std::unique_ptr<config::Source> file(std::string_view key, std::string_view meaning) override;
  // Writes the absolute path back into the document.
  std::filesystem::path relative_file(std::string_view key, std::string_view meaning) override;
  std::optional<std::filesystem::path> optional_relative_file(std::string_view key, std::string_view meaning) override;
  void finish() override { static_cast<const MappingReader*>(this)->finish(); }
  [[noreturn]] void fail(std::string_view key, const std::string& message) override {
    static_cast<const MappingReader*>(this)->fail(key, message);
  }
  [[noreturn]] void fail_section(const std::string& message) override { fail_at(node_, key_path_, message); }
  const std::string& file() const { return file_; }
  std::string path_of(std::string_view key) const;

 private:
  std::string string(std::string_view key);
  std::optional<std::string> optional_string(std::string_view key);
  // A non-empty list of at most max_rows equally long, non-empty lists of at most max_rows
  // numbers within the spec (matrix rows).
  std::vector<std::vector<double>> number_rows(std::string_view key, const config::Number& spec, std::size_t max_rows);
  // A non-empty list of at most max_count mappings, each read with its own path `key[i]`.
  std::vector<MappingReader> mappings(std::string_view key, std::size_t max_count);
  MappingReader mapping(std::string_view key);
  // Marks the key as known to finish() (and logs it).
  void accept(std::string_view key);
  YAML::Node required(std::string_view key);
  // The list at `key`, refused when it is empty, not a list or longer than max_count.
  YAML::Node list(std::string_view key, std::size_t max_count, const std::string& of_what);
  double item(const YAML::Node& value, const std::string& path, const config::Number& spec) const;
  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& path, const std::string& message) const;

  YAML::Node node_;
  std::string file_;
  std::string key_path_;
  OverrideNodes overrides_;
  std::set<std::string> read_keys_;
};

}  // namespace rpsd::scenarios
