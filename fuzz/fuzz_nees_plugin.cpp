// libFuzzer target: the NEES/LabVIEW plugin protocol's answer lines, which a node reads from a
// lab site over TCP. Any input must give a definite verdict; an accepted answer must be
// consistent (at most kMaxValues values, each finite, its fields inside the line) and its
// values must write back into a line that parses to the same values to %.10E's 11 digits.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rpsd/node/nees_plugin_messages.h"

namespace np = rpsd::node::nees_plugin;

namespace {

bool inside(std::string_view part, std::string_view whole) {
  return part.empty() || (part.data() >= whole.data() && part.data() + part.size() <= whole.data() + whole.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view line(reinterpret_cast<const char*>(data), size);
  np::Fields fields;
  if (np::split_fields(line, fields)) {
    if (fields.count < 1 || fields.count > np::kMaxFields) __builtin_trap();
    for (std::size_t f = 0; f < fields.count; ++f) {
      if (!inside(fields.field[f], line)) __builtin_trap();
    }
  }
  double number = 0.0;
  if (np::parse_number(line, number) && !std::isfinite(number)) __builtin_trap();
  np::ControlPointAnswer answer;
  if (np::parse_control_point_answer(line, answer) != np::AnswerError::kNone) return 0;
  if (answer.count > np::kMaxValues || !inside(answer.transaction, line) || !inside(answer.control_point, line))
    __builtin_trap();
  np::LineWriter writer;
  writer.begin("OK");
  writer.field("0");
  writer.field("T");
  writer.field("CP");
  for (std::size_t v = 0; v < answer.count; ++v) {
    if (!std::isfinite(answer.values[v].value)) __builtin_trap();
    writer.field(np::axis_word(answer.values[v].axis));
    writer.field(np::parameter_word(answer.values[v].parameter));
    writer.number(answer.values[v].value);
  }
  if (!writer.end()) return 0;  // more than a line holds: refused when written, never sent
  np::ControlPointAnswer again;
  if (np::parse_control_point_answer(writer.text(), again) != np::AnswerError::kNone || again.count != answer.count)
    __builtin_trap();
  for (std::size_t v = 0; v < answer.count; ++v) {
    const double a = answer.values[v].value, b = again.values[v].value;
    if (again.values[v].axis != answer.values[v].axis || again.values[v].parameter != answer.values[v].parameter ||
        std::abs(a - b) > 1e-10 * std::abs(a) + 1e-300)  // subnormals carry fewer digits
      __builtin_trap();
  }
  return 0;
}
