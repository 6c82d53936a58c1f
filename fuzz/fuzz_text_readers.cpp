// libFuzzer target: the plain-text and two-column readers. The first byte chooses the
// reader, unit, column and header lines; the rest is the file text. Only RecordError with
// the source name in front may come out; accepted records must be consistent.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rpsd/ground_motion/record_error.h"
#include "rpsd/ground_motion/text_readers.h"

namespace gm = rpsd::ground_motion;

namespace {

void check(const gm::GroundMotionRecord& record) {
  if (record.acceleration_m_per_s2.empty() || !(record.dt_s > 0.0) || !std::isfinite(record.dt_s)) {
    __builtin_trap();
  }
  for (const double a : record.acceleration_m_per_s2) {
    if (!std::isfinite(a)) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t selector = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const auto unit = static_cast<gm::AccelerationUnit>((selector >> 2) % 3);
  const std::size_t column = (selector >> 4) & 3;
  const std::size_t skip = (selector >> 6) & 1;
  try {
    switch (selector & 3) {
      case 0:
      case 1: {  // plain, every value in order
        gm::PlainTextOptions o;
        o.dt_s = 0.01;
        o.unit = unit;
        o.skip_lines = skip;
        if (selector & 1) o.expected_points = 5;
        check(gm::parse_plain_text(text, "fuzz.txt", o));
        break;
      }
      case 2: {  // plain, one column of a table
        gm::PlainTextOptions o;
        o.dt_s = 0.005;
        o.unit = unit;
        o.skip_lines = skip;
        o.column = column;
        check(gm::parse_plain_text(text, "fuzz.txt", o));
        break;
      }
      default: {  // time, acceleration
        gm::TimeAccelerationOptions o;
        o.unit = unit;
        o.skip_lines = skip;
        o.acceleration_column = column == 0 ? 1 : column;
        check(gm::parse_time_acceleration(text, "fuzz.txt", o));
        break;
      }
    }
  } catch (const rpsd::ground_motion::RecordError& e) {
    if (std::string_view(e.what()).rfind("fuzz.txt", 0) != 0) __builtin_trap();
  }
  return 0;
}
