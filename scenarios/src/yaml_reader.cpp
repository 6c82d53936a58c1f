#include "rpsd/scenarios/yaml_reader.h"

#include <cmath>
#include <memory>

#include <fstream>
#include <sstream>
#include "rpsd/config/key_table.h"

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

}  // namespace

YAML::Node load_yaml_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ConfigError(file.string() + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_yaml_text(text.str(), file.string());
}

YAML::Node parse_yaml_text(const std::string& text, const std::string& name) {
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw ConfigError(name + ": expected a mapping of keys at the top level");
    return root;
  } catch (const YAML::Exception& e) {
    throw ConfigError(location(name, e.mark) + ": YAML syntax error: " + e.msg);
  }
}

MappingReader::MappingReader(YAML::Node node, std::string file, std::string key_path)
    : node_(node), file_(std::move(file)), key_path_(std::move(key_path)) {
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

void MappingReader::fail_at(const YAML::Node& node, const std::string& path, const std::string& message) const {
  throw ConfigError(location(file_, node.Mark()) + ": " + (path.empty() ? std::string("(document)") : path) + ": " +
                    message);
}

void MappingReader::fail(std::string_view key, const std::string& message) const {
  const YAML::Node value = node_[std::string(key)];
  fail_at(value ? value : node_, path_of(key), message);
}

bool MappingReader::has(std::string_view key) {
  read_keys_.insert(std::string(key));
  return static_cast<bool>(node_[std::string(key)]);
}

YAML::Node MappingReader::required(std::string_view key) {
  read_keys_.insert(std::string(key));
  YAML::Node value = node_[std::string(key)];
  if (!value) fail_at(node_, path_of(key), "required key is missing");
  return value;
}

double MappingReader::parse_number(const YAML::Node& value, std::string_view key) const {
  double result = 0.0;
  if (!value.IsScalar() || !YAML::convert<double>::decode(value, result) || !std::isfinite(result)) {
    fail_at(value, path_of(key), "expected a number, got " + describe(value));
  }
  return result;
}

double MappingReader::number(std::string_view key) { return parse_number(required(key), key); }

double MappingReader::positive_number(std::string_view key) {
  const YAML::Node value = required(key);
  const double v = parse_number(value, key);
  if (!(v > 0.0)) fail_at(value, path_of(key), "expected a positive number, got " + describe(value));
  return v;
}

double MappingReader::non_negative_number(std::string_view key) {
  const YAML::Node value = required(key);
  const double v = parse_number(value, key);
  if (v < 0.0) fail_at(value, path_of(key), "expected zero or a positive number, got " + describe(value));
  return v;
}

double MappingReader::number_or(std::string_view key, double fallback) { return has(key) ? number(key) : fallback; }
double MappingReader::positive_number_or(std::string_view key, double fallback) {
  return has(key) ? positive_number(key) : fallback;
}
double MappingReader::non_negative_number_or(std::string_view key, double fallback) {
  return has(key) ? non_negative_number(key) : fallback;
}

bool MappingReader::boolean_or(std::string_view key, bool fallback) {
  read_keys_.insert(std::string(key));
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

std::optional<std::string> MappingReader::optional_string(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return string(key);
}

std::vector<double> MappingReader::positive_numbers(std::string_view key) {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() == 0) {
    fail_at(value, path_of(key), "expected a non-empty list of numbers, got " + describe(value));
  }
  std::vector<double> numbers;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string item_path = path_of(key) + '[' + std::to_string(i) + ']';
    double v = 0.0;
    if (!value[i].IsScalar() || !YAML::convert<double>::decode(value[i], v) || !std::isfinite(v) || !(v > 0.0)) {
      fail_at(value[i], item_path, "expected a positive number, got " + describe(value[i]));
    }
    numbers.push_back(v);
  }
  return numbers;
}

std::vector<double> MappingReader::numbers(std::string_view key) {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() == 0) {
    fail_at(value, path_of(key), "expected a non-empty list of numbers, got " + describe(value));
  }
  std::vector<double> result;
  for (std::size_t i = 0; i < value.size(); ++i) {
    double v = 0.0;
    if (!value[i].IsScalar() || !YAML::convert<double>::decode(value[i], v) || !std::isfinite(v)) {
      fail_at(value[i], path_of(key) + '[' + std::to_string(i) + ']', "expected a number, got " + describe(value[i]));
    }
    result.push_back(v);
  }
  return result;
}

std::vector<std::vector<double>> MappingReader::number_rows(std::string_view key) {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() == 0) {
    fail_at(value, path_of(key), "expected a list of rows (lists of numbers), got " + describe(value));
  }
  std::vector<std::vector<double>> rows;
  for (std::size_t r = 0; r < value.size(); ++r) {
    const YAML::Node row = value[r];
    const std::string row_path = path_of(key) + '[' + std::to_string(r) + ']';
    if (!row.IsSequence() || row.size() == 0)
      fail_at(row, row_path, "expected a list of numbers, got " + describe(row));
    if (!rows.empty() && row.size() != rows.front().size()) {
      fail_at(row, row_path,
              "has " + std::to_string(row.size()) + " entries, row 0 has " + std::to_string(rows.front().size()));
    }
    std::vector<double> numbers;
    for (std::size_t c = 0; c < row.size(); ++c) {
      double v = 0.0;
      if (!row[c].IsScalar() || !YAML::convert<double>::decode(row[c], v) || !std::isfinite(v)) {
        fail_at(row[c], row_path + '[' + std::to_string(c) + ']', "expected a number, got " + describe(row[c]));
      }
      numbers.push_back(v);
    }
    rows.push_back(std::move(numbers));
  }
  return rows;
}

long MappingReader::whole_number(std::string_view key, long minimum, long maximum) {
  const YAML::Node value = required(key);
  const double v = parse_number(value, key);
  if (v != std::floor(v) || v < static_cast<double>(minimum) || v > static_cast<double>(maximum)) {
    fail_at(value, path_of(key),
            "expected a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum) + ", got " +
                describe(value));
  }
  return static_cast<long>(v);
}

long MappingReader::whole_number_or(std::string_view key, long minimum, long maximum, long fallback) {
  return has(key) ? whole_number(key, minimum, maximum) : fallback;
}

std::vector<MappingReader> MappingReader::mappings(std::string_view key) {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() == 0)
    fail_at(value, path_of(key), "expected a non-empty list, got " + describe(value));
  std::vector<MappingReader> result;
  for (std::size_t i = 0; i < value.size(); ++i)
    result.emplace_back(value[i], file_, path_of(key) + '[' + std::to_string(i) + ']');
  return result;
}

MappingReader MappingReader::mapping(std::string_view key) {
  const YAML::Node value = required(key);
  return MappingReader(value, file_, path_of(key));
}

std::optional<MappingReader> MappingReader::optional_mapping(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return mapping(key);
}

void MappingReader::finish() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (!read_keys_.contains(key)) fail_at(entry.first, path_of(key), "unknown key");
  }
}

double MappingReader::checked(double value, std::string_view key, const config::Number& spec) const {
  if (!spec.admits(value)) {
    const YAML::Node node = node_[std::string(key)];
    fail_at(node ? node : node_, path_of(key),
            "expected a number " + config::range_text(spec) + ", got " + describe(node));
  }
  return value;
}

namespace {

// The positive and non-negative ranges read as they always did, with the same messages.
bool is_positive(const config::Number& spec) { return spec.min == 0.0 && spec.min_open && std::isinf(spec.max); }
bool is_non_negative(const config::Number& spec) { return spec.min == 0.0 && !spec.min_open && std::isinf(spec.max); }

}  // namespace

double MappingReader::number(std::string_view key, const config::Number& spec) {
  if (is_positive(spec)) return positive_number(key);
  if (is_non_negative(spec)) return non_negative_number(key);
  return checked(number(key), key, spec);
}

double MappingReader::number_or(std::string_view key, double fallback, const config::Number& spec) {
  return has(key) ? number(key, spec) : fallback;
}

std::vector<double> MappingReader::numbers(std::string_view key, const config::Number& spec) {
  if (is_positive(spec)) return positive_numbers(key);
  std::vector<double> values = numbers(key);
  const YAML::Node list = node_[std::string(key)];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!spec.admits(values[i])) {
      fail_at(list[i], path_of(key) + '[' + std::to_string(i) + ']',
              "expected a number " + config::range_text(spec) + ", got " + describe(list[i]));
    }
  }
  return values;
}

long MappingReader::whole_number(std::string_view key, long minimum, long maximum, std::string_view) {
  return whole_number(key, minimum, maximum);
}

long MappingReader::whole_number_or(std::string_view key, long minimum, long maximum, long fallback, std::string_view) {
  return whole_number_or(key, minimum, maximum, fallback);
}

bool MappingReader::boolean_or(std::string_view key, bool fallback, std::string_view) {
  return boolean_or(key, fallback);
}

std::string MappingReader::choice(std::string_view key, const std::vector<std::string_view>& choices,
                                  std::string_view) {
  const std::string value = string(key);
  for (const auto& c : choices) {
    if (value == c) return value;
  }
  std::string listed;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) listed += i + 1 == choices.size() ? " or " : ", ";
    listed += choices[i];
  }
  fail(key, "expected " + listed + ", got \"" + value + "\"");
}

std::unique_ptr<config::Source> MappingReader::section(std::string_view key, std::string_view) {
  return std::make_unique<MappingReader>(mapping(key));
}

std::unique_ptr<config::Source> MappingReader::file(std::string_view key, std::string_view) {
  const std::filesystem::path path = std::filesystem::path(file_).parent_path() / string(key);
  if (!std::filesystem::is_regular_file(path)) fail(key, "no such file: " + path.string());
  return std::make_unique<MappingReader>(load_yaml_file(path), path.string(), "");
}

}  // namespace rpsd::scenarios
