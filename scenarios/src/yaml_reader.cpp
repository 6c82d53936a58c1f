#include "rpsd/scenarios/yaml_reader.h"

#include <cmath>
#include <memory>
#include <sstream>

#include "rpsd/config/closest_name.h"
#include "rpsd/config/input_file.h"
#include "rpsd/config/key_table.h"
#include "rpsd/config/kind_list.h"

namespace rpsd::scenarios {
namespace {

std::string location(const std::string& file, const YAML::Mark& mark) {
  std::ostringstream out;
  out << file;
  if (!mark.is_null()) out << ':' << mark.line + 1 << ':' << mark.column + 1;
  return out.str();
}

std::string describe(const YAML::Node& value) {
  if (value.IsScalar()) return '"' + value.Scalar() + '"';
  if (value.IsSequence()) return "a list";
  if (value.IsMap()) return "a mapping";
  return "nothing";
}

// The positive and non-negative ranges keep the words they always had.
std::string expected_number(const config::Number& spec) {
  const bool unbounded = std::isinf(spec.max);
  if (spec.min == 0.0 && spec.min_open && unbounded) return "a positive number";
  if (spec.min == 0.0 && !spec.min_open && unbounded) return "zero or a positive number";
  return "a number " + config::range_text(spec);
}

std::set<std::string>* accepted_log = nullptr;

// "a[3].b[0].c" -> "a[].b[].c", as the reference writes a list's items.
std::string without_indices(const std::string& path) {
  std::string out;
  bool in_index = false;
  for (char c : path) {
    if (c == ']') in_index = false;
    if (!in_index) out += c;
    if (c == '[') in_index = true;
  }
  return out;
}

}  // namespace

void log_accepted_keys(std::set<std::string>* log) { accepted_log = log; }

std::string read_yaml_file_text(const std::filesystem::path& file) {
  try {
    config::InputFile in(file, config::kMaxYamlFileBytes, "YAML file");
    return in.read_all();
  } catch (const config::InputFileError& e) {
    throw ConfigError(e.what());
  }
}

YAML::Node load_yaml_file(const std::filesystem::path& file) {
  return parse_yaml_text(read_yaml_file_text(file), file.string());
}

YAML::Node parse_yaml_text(const std::string& text, const std::string& name) {
  if (text.size() > config::kMaxYamlFileBytes) {
    throw ConfigError(name + ": has " + std::to_string(text.size()) + " bytes; a YAML file may have at most " +
                      config::byte_size_text(config::kMaxYamlFileBytes));
  }
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw ConfigError(name + ": expected a mapping of keys at the top level");
    return root;
  } catch (const YAML::Exception& e) {
    // yaml-cpp says "illegal map value" or the like for a tab; name the tab instead.
    std::size_t line = 1, start = 0;
    for (std::size_t end; start < text.size(); start = end + 1, ++line) {
      end = std::min(text.find('\n', start), text.size());
      const std::size_t first = text.find_first_not_of(' ', start);
      if (first < end && text[first] == '\t') {
        throw ConfigError(name + ":" + std::to_string(line) + ":" + std::to_string(first - start + 1) +
                          ": a tab in the indentation; YAML allows only spaces there");
      }
    }
    throw ConfigError(location(name, e.mark) + ": YAML syntax error: " + e.msg);
  }
}

MappingReader::MappingReader(YAML::Node node, std::string file, std::string key_path, OverrideNodes overrides)
    : node_(node), file_(std::move(file)), key_path_(std::move(key_path)), overrides_(std::move(overrides)) {
  if (!node_.IsMap()) fail_at(node_, key_path_, "expected a mapping of keys, got " + describe(node_));
  // YAML keeps both copies of a repeated key and lookups see only one: reject it instead.
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) fail_at(entry.first, key_path_, "keys must be plain words");
    if (!seen.insert(entry.first.Scalar()).second)
      fail_at(entry.first, path_of(entry.first.Scalar()), "given more than once");
  }
}

std::string MappingReader::path_of(std::string_view key) const {
  return key_path_.empty() ? std::string(key) : key_path_ + '.' + std::string(key);
}

namespace {

bool within(const YAML::Node& tree, const YAML::Node& node) {
  if (tree.is(node)) return true;
  if (tree.IsMap()) {
    for (const auto& entry : tree)
      if (entry.first.is(node) || within(entry.second, node)) return true;
  } else if (tree.IsSequence()) {
    for (const auto& item : tree)
      if (within(item, node)) return true;
  }
  return false;
}

}  // namespace

void MappingReader::fail_at(const YAML::Node& node, const std::string& path, const std::string& message) const {
  const std::string what = (path.empty() ? std::string("(document)") : path) + ": " + message;
  if (overrides_) {
    for (const OverrideNode& o : *overrides_)
      if (within(o.value, node)) throw ConfigError(o.origin + ": " + what);
  }
  throw ConfigError(location(file_, node.Mark()) + ": " + what);
}

void MappingReader::fail(std::string_view key, const std::string& message) const {
  const YAML::Node value = node_[std::string(key)];
  fail_at(value ? value : node_, path_of(key), message);
}

void MappingReader::accept(std::string_view key) {
  read_keys_.insert(std::string(key));
  if (accepted_log) accepted_log->insert(without_indices(path_of(key)));
}

bool MappingReader::has(std::string_view key) {
  accept(key);
  return static_cast<bool>(node_[std::string(key)]);
}

YAML::Node MappingReader::required(std::string_view key) {
  accept(key);
  YAML::Node value = node_[std::string(key)];
  if (!value) {
    // A misspelling of this key is the likelier mistake: name it, not the missing one.
    for (const auto& entry : node_) {
      const std::string given = entry.first.Scalar();
      if (!read_keys_.contains(given) && config::closest_name(given, {key}))
        fail_at(entry.first, path_of(given), "unknown key (did you mean \"" + std::string(key) + "\"?)");
    }
    fail_at(node_, path_of(key), "required key is missing");
  }
  return value;
}

YAML::Node MappingReader::list(std::string_view key, std::size_t max_count, const std::string& of_what) {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() == 0) {
    fail_at(value, path_of(key), "expected a non-empty list of " + of_what + ", got " + describe(value));
  }
  if (value.size() > max_count) {
    fail_at(value, path_of(key),
            "expected at most " + std::to_string(max_count) + " " + of_what + ", got " + std::to_string(value.size()));
  }
  return value;
}

double MappingReader::item(const YAML::Node& value, const std::string& path, const config::Number& spec) const {
  double result = 0.0;
  if (!value.IsScalar() || !YAML::convert<double>::decode(value, result) || !std::isfinite(result)) {
    fail_at(value, path, "expected a number, got " + describe(value));
  }
  if (!spec.admits(result)) fail_at(value, path, "expected " + expected_number(spec) + ", got " + describe(value));
  return result;
}

double MappingReader::number(std::string_view key, const config::Number& spec) {
  return item(required(key), path_of(key), spec);
}

double MappingReader::number_or(std::string_view key, double fallback, const config::Number& spec) {
  return has(key) ? number(key, spec) : fallback;
}

std::vector<double> MappingReader::numbers(std::string_view key, const config::Number& spec, std::size_t max_count) {
  const YAML::Node value = list(key, max_count, "numbers");
  std::vector<double> result;
  result.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    result.push_back(item(value[i], path_of(key) + '[' + std::to_string(i) + ']', spec));
  }
  return result;
}

std::vector<std::vector<double>> MappingReader::number_rows(std::string_view key, const config::Number& spec,
                                                            std::size_t max_rows) {
  const YAML::Node value = list(key, max_rows, "rows (lists of numbers)");
  std::vector<std::vector<double>> rows;
  for (std::size_t r = 0; r < value.size(); ++r) {
    const YAML::Node row = value[r];
    const std::string row_path = path_of(key) + '[' + std::to_string(r) + ']';
    if (!row.IsSequence() || row.size() == 0)
      fail_at(row, row_path, "expected a list of numbers, got " + describe(row));
    if (row.size() > max_rows) {
      fail_at(row, row_path,
              "expected at most " + std::to_string(max_rows) + " numbers, got " + std::to_string(row.size()));
    }
    if (!rows.empty() && row.size() != rows.front().size()) {
      fail_at(row, row_path,
              "has " + std::to_string(row.size()) + " entries, row 0 has " + std::to_string(rows.front().size()));
    }
    std::vector<double> numbers;
    for (std::size_t c = 0; c < row.size(); ++c) {
      numbers.push_back(item(row[c], row_path + '[' + std::to_string(c) + ']', spec));
    }
    rows.push_back(std::move(numbers));
  }
  return rows;
}

long MappingReader::whole_number(std::string_view key, long minimum, long maximum, std::string_view) {
  const YAML::Node value = required(key);
  double v = 0.0;
  if (!value.IsScalar() || !YAML::convert<double>::decode(value, v) || !std::isfinite(v)) {
    fail_at(value, path_of(key), "expected a number, got " + describe(value));
  }
  // The range is checked on the double, before any cast.
  if (v != std::floor(v) || v < static_cast<double>(minimum) || v > static_cast<double>(maximum)) {
    fail_at(value, path_of(key),
            "expected a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum) + ", got " +
                describe(value));
  }
  return static_cast<long>(v);
}

long MappingReader::whole_number_or(std::string_view key, long minimum, long maximum, long fallback,
                                    std::string_view meaning) {
  return has(key) ? whole_number(key, minimum, maximum, meaning) : fallback;
}

bool MappingReader::boolean_or(std::string_view key, bool fallback, std::string_view) {
  accept(key);
  const YAML::Node value = node_[std::string(key)];
  if (!value) return fallback;
  bool result = false;
  if (!value.IsScalar() || !YAML::convert<bool>::decode(value, result)) {
    fail_at(value, path_of(key), "expected true or false, got " + describe(value));
  }
  return result;
}

std::string MappingReader::string(std::string_view key) {
  const YAML::Node value = required(key);
  if (!value.IsScalar()) fail_at(value, path_of(key), "expected a string, got " + describe(value));
  return value.Scalar();
}

std::filesystem::path MappingReader::relative_file(std::string_view key, std::string_view meaning) {
  const std::filesystem::path path =
      std::filesystem::absolute(std::filesystem::path(file_).parent_path() / text(key, meaning)).lexically_normal();
  node_[std::string(key)] = path.string();
  return path;
}

std::optional<std::filesystem::path> MappingReader::optional_relative_file(std::string_view key,
                                                                           std::string_view meaning) {
  if (!has(key)) return std::nullopt;
  return relative_file(key, meaning);
}

std::optional<std::string> MappingReader::optional_string(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return string(key);
}

std::vector<MappingReader> MappingReader::mappings(std::string_view key, std::size_t max_count) {
  const YAML::Node value = list(key, max_count, "entries");
  std::vector<MappingReader> result;
  for (std::size_t i = 0; i < value.size(); ++i)
    result.emplace_back(value[i], file_, path_of(key) + '[' + std::to_string(i) + ']', overrides_);
  return result;
}

MappingReader MappingReader::mapping(std::string_view key) {
  const YAML::Node value = required(key);
  return MappingReader(value, file_, path_of(key), overrides_);
}

void MappingReader::finish() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (!read_keys_.contains(key)) {
      const std::vector<std::string_view> known(read_keys_.begin(), read_keys_.end());
      fail_at(entry.first, path_of(key), "unknown key" + config::did_you_mean(key, known));
    }
  }
}

std::string MappingReader::choice(std::string_view key, const std::vector<std::string_view>& choices,
                                  std::string_view) {
  const std::string value = string(key);
  for (const auto& c : choices) {
    if (value == c) return value;
  }
  fail(key, "expected " + config::listed(choices) + ", got \"" + value + "\"" + config::did_you_mean(value, choices));
}

std::optional<double> MappingReader::optional_number(std::string_view key, const config::Number& spec) {
  if (!has(key)) return std::nullopt;
  return number(key, spec);
}

std::optional<std::string> MappingReader::optional_text(std::string_view key, std::string_view) {
  return optional_string(key);
}

std::optional<std::vector<double>> MappingReader::optional_numbers(std::string_view key, const config::Number& spec,
                                                                   std::size_t max_count) {
  if (!has(key)) return std::nullopt;
  return numbers(key, spec, max_count);
}

std::optional<std::vector<std::string>> MappingReader::optional_texts(std::string_view key, std::string_view,
                                                                      std::size_t max_count) {
  if (!has(key)) return std::nullopt;
  const YAML::Node value = list(key, max_count, "texts");
  std::vector<std::string> result;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!value[i].IsScalar()) {
      fail_at(value[i], path_of(key) + '[' + std::to_string(i) + ']', "expected a text, got " + describe(value[i]));
    }
    result.push_back(value[i].Scalar());
  }
  return result;
}

std::unique_ptr<config::Source> MappingReader::optional_section(std::string_view key, std::string_view meaning) {
  if (!has(key)) return nullptr;
  return section(key, meaning);
}

std::string MappingReader::choice_or(std::string_view key, const std::vector<std::string_view>& choices,
                                     std::string_view fallback, std::string_view meaning) {
  return has(key) ? choice(key, choices, meaning) : std::string(fallback);
}

std::vector<std::vector<double>> MappingReader::matrix(std::string_view key, const config::Number& entry,
                                                       std::size_t max_rows) {
  const YAML::Node value = required(key);
  if (value.IsSequence() && value.size() > 0 && value[0].IsSequence()) {
    const config::Number any_sign{entry.unit, entry.meaning, -entry.max, entry.max};
    return number_rows(key, any_sign, max_rows);
  }
  if (value.IsSequence()) {
    const std::vector<double> diagonal = numbers(key, entry, max_rows);
    std::vector<std::vector<double>> rows(diagonal.size(), std::vector<double>(diagonal.size(), 0.0));
    for (std::size_t i = 0; i < diagonal.size(); ++i) rows[i][i] = diagonal[i];
    return rows;
  }
  return {{number(key, entry)}};
}

std::vector<std::unique_ptr<config::Source>> MappingReader::sections(std::string_view key, std::size_t max_count,
                                                                     std::string_view) {
  std::vector<std::unique_ptr<config::Source>> result;
  for (auto& m : mappings(key, max_count)) result.push_back(std::make_unique<MappingReader>(std::move(m)));
  return result;
}

std::unique_ptr<config::Source> MappingReader::section(std::string_view key, std::string_view) {
  return std::make_unique<MappingReader>(mapping(key));
}

std::unique_ptr<config::Source> MappingReader::file(std::string_view key, std::string_view meaning) {
  const std::filesystem::path path = relative_file(key, meaning);
  try {
    config::check_input_file(path, config::kMaxYamlFileBytes, "YAML file");
  } catch (const config::InputFileError& e) {
    fail(key, e.what());
  }
  return std::make_unique<MappingReader>(load_yaml_file(path), path.string(), "");
}

}  // namespace rpsd::scenarios
