// The lines of the NEES/LabVIEW plugin protocol as OpenFresco's ECLabVIEW client writes and
// reads them (docs/lab-controllers.md): tab-separated fields, one line per message,
// '\n' at its end. Lines are written into and parsed from fixed buffers (std::to_chars,
// std::from_chars), so that a control period's exchange allocates nothing.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <ctime>
#include <span>
#include <string>
#include <string_view>

namespace rpsd::node::nees_plugin {

// The longest line rpsd writes or takes (OpenFresco's own buffer holds 512 bytes).
inline constexpr std::size_t kMaxLineBytes = 1024;
// The longest control point or session name (OpenFresco's answer parser holds 16).
inline constexpr std::size_t kMaxNameBytes = 64;
// Fields in one line: a get-control-point answer of 8 channels has 4 + 8 * 2 * 3.
inline constexpr std::size_t kMaxFields = 64;
// Values in one control point's answer.
inline constexpr std::size_t kMaxValues = (kMaxFields - 4) / 3;

enum class Axis : std::uint8_t { kX, kY, kZ };
// A translation is commanded as a displacement and reacts with a force; a rotation as a
// rotation, reacting with a moment.
enum class Motion : std::uint8_t { kTranslation, kRotation };
enum class Parameter : std::uint8_t { kDisplacement, kForce, kRotation, kMoment };

std::string_view axis_word(Axis axis) noexcept;
std::string_view parameter_word(Parameter parameter) noexcept;
bool parse_axis(std::string_view word, Axis& axis) noexcept;
bool parse_parameter(std::string_view word, Parameter& parameter) noexcept;
inline Parameter commanded(Motion motion) noexcept {
  return motion == Motion::kTranslation ? Parameter::kDisplacement : Parameter::kRotation;
}
inline Parameter reaction(Motion motion) noexcept {
  return motion == Motion::kTranslation ? Parameter::kForce : Parameter::kMoment;
}

// A name may go on the wire: 1 to kMaxNameBytes printable ASCII characters, no space or tab.
bool valid_name(std::string_view name) noexcept;

// Builds one line in a fixed buffer. Real-time safe.
class LineWriter {
 public:
  void begin(std::string_view command) noexcept;
  void field(std::string_view text) noexcept;  // a tab, then the text
  void number(double value) noexcept;          // a tab, then the value as OpenFresco's %.10E
  // Ends the line with '\n'; false when it did not fit or a number was not finite.
  bool end() noexcept;
  std::string_view text() const noexcept { return {buffer_.data(), size_}; }
  std::span<const std::byte> bytes() const noexcept;

 private:
  void append(std::string_view text) noexcept;
  std::array<char, kMaxLineBytes> buffer_{};
  std::size_t size_ = 0;
  bool failed_ = false;
};

// Where one channel goes on the wire: its control point (an index into the names) and axis.
struct ChannelPoint {
  std::size_t control_point = 0;
  Axis axis = Axis::kX;
  Motion motion = Motion::kTranslation;
};

// propose, as ECLabVIEW::control() lays it out: the transaction, the first control point's
// name and its (axis, parameter, value) triples, then "control-point", the next name and its
// triples. `values` holds one value per channel, in the site's units. Real-time safe.
bool write_propose(LineWriter& line, std::string_view transaction, std::span<const std::string> control_points,
                   std::span<const ChannelPoint> channels, std::span<const double> values) noexcept;
// get-control-point with the transaction and every control point's name. Real-time safe.
bool write_get_control_point(LineWriter& line, std::string_view transaction,
                             std::span<const std::string> control_points) noexcept;

// The fields of one line: views into it, its '\n' (and a '\r' before it) left out.
struct Fields {
  std::array<std::string_view, kMaxFields> field{};
  std::size_t count = 0;
};
// False when the line has more than kMaxFields fields. Real-time safe.
bool split_fields(std::string_view line, Fields& fields) noexcept;
// An answer is taken when its first field is OK; anything else is the site refusing.
inline bool accepted(const Fields& fields) noexcept { return fields.count > 0 && fields.field[0] == "OK"; }

// A finite number as a site writes it (%.10E, %g, %f, a leading '+'); false unless the whole
// field is one. Real-time safe.
bool parse_number(std::string_view text, double& value) noexcept;

// One line of the answer to get-control-point:
//   OK <status> <transaction> <control point> (<axis> <parameter> <value>)...
struct ControlPointValue {
  Axis axis = Axis::kX;
  Parameter parameter = Parameter::kDisplacement;
  double value = 0.0;
};
struct ControlPointAnswer {
  std::string_view status, transaction, control_point;
  std::array<ControlPointValue, kMaxValues> values{};
  std::size_t count = 0;
};
enum class AnswerError : std::uint8_t {
  kNone,
  kRefused,        // the first field is not OK
  kTooFewFields,   // no transaction or control point
  kTooManyFields,  // more than kMaxFields
  kBadTriple,      // an unknown axis or parameter, or a triple cut short
  kBadNumber,      // a value that is no finite number
};
const char* answer_error_name(AnswerError error) noexcept;
AnswerError parse_control_point_answer(std::string_view line, ControlPointAnswer& answer) noexcept;

// Transaction ids, unique within a process's run and across runs: OpenFresco's prefix and
// the local time of the session's start to the second (its own ids), then "n" and a counter
// that never repeats (OpenFresco's repeat within a second).
class TransactionIds {
 public:
  // Not real-time safe (local time).
  void begin(std::time_t now);
  // The next id. Real-time safe.
  std::string_view next() noexcept;
  std::string_view current() const noexcept { return {id_.data(), size_}; }

 private:
  std::array<char, 48> id_{};
  std::size_t prefix_ = 0, size_ = 0;
  std::uint64_t counter_ = 0;
};

}  // namespace rpsd::node::nees_plugin
