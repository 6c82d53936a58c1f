#include "rpsd/node/nees_plugin_messages.h"

#include <charconv>
#include <cmath>
#include <cstring>

namespace rpsd::node::nees_plugin {

namespace {
constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};
constexpr std::array<std::string_view, 4> kParameters{"displacement", "force", "rotation", "moment"};
}  // namespace

std::string_view axis_word(Axis axis) noexcept { return kAxes[static_cast<std::size_t>(axis)]; }
std::string_view parameter_word(Parameter parameter) noexcept {
  return kParameters[static_cast<std::size_t>(parameter)];
}

bool parse_axis(std::string_view word, Axis& axis) noexcept {
  for (std::size_t i = 0; i < kAxes.size(); ++i) {
    if (word == kAxes[i]) {
      axis = static_cast<Axis>(i);
      return true;
    }
  }
  return false;
}

bool parse_parameter(std::string_view word, Parameter& parameter) noexcept {
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    if (word == kParameters[i]) {
      parameter = static_cast<Parameter>(i);
      return true;
    }
  }
  return false;
}

bool valid_name(std::string_view name) noexcept {
  if (name.empty() || name.size() > kMaxNameBytes) return false;
  for (const char c : name) {
    if (c <= ' ' || c > '~') return false;
  }
  return true;
}

void LineWriter::append(std::string_view text) noexcept {
  if (failed_ || text.size() > buffer_.size() - size_) {
    failed_ = true;
    return;
  }
  std::memcpy(buffer_.data() + size_, text.data(), text.size());
  size_ += text.size();
}

void LineWriter::begin(std::string_view command) noexcept {
  size_ = 0;
  failed_ = false;
  append(command);
}

void LineWriter::field(std::string_view text) noexcept {
  append("\t");
  append(text);
}

void LineWriter::number(double value) noexcept {
  if (!std::isfinite(value)) {
    failed_ = true;
    return;
  }
  // printf's %.10E: one digit, ten decimals, an upper-case E and a signed exponent of at least
  // two digits, as to_chars writes it in lower case.
  std::array<char, 32> text{};
  const auto [end, error] =
      std::to_chars(text.data(), text.data() + text.size(), value, std::chars_format::scientific, 10);
  if (error != std::errc{}) {
    failed_ = true;
    return;
  }
  for (char* c = text.data(); c != end; ++c) {
    if (*c == 'e') *c = 'E';
  }
  field(std::string_view(text.data(), static_cast<std::size_t>(end - text.data())));
}

bool LineWriter::end() noexcept {
  append("\n");
  return !failed_;
}

std::span<const std::byte> LineWriter::bytes() const noexcept {
  return std::as_bytes(std::span<const char>(buffer_.data(), size_));
}

bool write_propose(LineWriter& line, std::string_view transaction, std::span<const std::string> control_points,
                   std::span<const ChannelPoint> channels, std::span<const double> values) noexcept {
  if (values.size() != channels.size()) return false;
  line.begin("propose");
  line.field(transaction);
  for (std::size_t p = 0; p < control_points.size(); ++p) {
    if (p > 0) line.field("control-point");
    line.field(control_points[p]);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      if (channels[c].control_point != p) continue;
      line.field(axis_word(channels[c].axis));
      line.field(parameter_word(commanded(channels[c].motion)));
      line.number(values[c]);
    }
  }
  return line.end();
}

bool write_get_control_point(LineWriter& line, std::string_view transaction,
                             std::span<const std::string> control_points) noexcept {
  line.begin("get-control-point");
  line.field(transaction);
  for (const std::string& name : control_points) line.field(name);
  return line.end();
}

bool split_fields(std::string_view line, Fields& fields) noexcept {
  if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  fields.count = 0;
  for (;;) {
    if (fields.count == kMaxFields) return false;
    const std::size_t tab = line.find('\t');
    fields.field[fields.count++] = line.substr(0, tab);
    if (tab == std::string_view::npos) return true;
    line.remove_prefix(tab + 1);
  }
}

bool parse_number(std::string_view text, double& value) noexcept {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return false;
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(parsed)) return false;
  value = parsed;
  return true;
}

const char* answer_error_name(AnswerError error) noexcept {
  switch (error) {
    case AnswerError::kNone:
      return "none";
    case AnswerError::kRefused:
      return "refused";
    case AnswerError::kTooFewFields:
      return "too few fields";
    case AnswerError::kTooManyFields:
      return "too many fields";
    case AnswerError::kBadTriple:
      return "an unknown axis or parameter";
    case AnswerError::kBadNumber:
      return "a value that is no finite number";
  }
  return "unknown";
}

AnswerError parse_control_point_answer(std::string_view line, ControlPointAnswer& answer) noexcept {
  Fields fields;
  if (!split_fields(line, fields)) return AnswerError::kTooManyFields;
  if (!accepted(fields)) return AnswerError::kRefused;
  if (fields.count < 4) return AnswerError::kTooFewFields;
  answer.status = fields.field[1];
  answer.transaction = fields.field[2];
  answer.control_point = fields.field[3];
  answer.count = 0;
  if ((fields.count - 4) % 3 != 0) return AnswerError::kBadTriple;
  for (std::size_t f = 4; f + 2 < fields.count; f += 3) {
    ControlPointValue& v = answer.values[answer.count];
    if (!parse_axis(fields.field[f], v.axis) || !parse_parameter(fields.field[f + 1], v.parameter))
      return AnswerError::kBadTriple;
    if (!parse_number(fields.field[f + 2], v.value)) return AnswerError::kBadNumber;
    ++answer.count;
  }
  return AnswerError::kNone;
}

void TransactionIds::begin(std::time_t now) {
  std::tm local{};
  ::localtime_r(&now, &local);
  const std::size_t n = std::strftime(id_.data(), id_.size(), "OPFTransaction%Y%m%d%H%M%Sn", &local);
  prefix_ = size_ = n;
}

std::string_view TransactionIds::next() noexcept {
  ++counter_;
  const auto [end, error] = std::to_chars(id_.data() + prefix_, id_.data() + id_.size(), counter_);
  size_ = error == std::errc{} ? static_cast<std::size_t>(end - id_.data()) : prefix_;
  return current();
}

}  // namespace rpsd::node::nees_plugin
