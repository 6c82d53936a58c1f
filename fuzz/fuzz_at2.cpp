// libFuzzer target: PEER AT2 text from memory. Any input may be rejected, but only with a
// RecordError whose message starts with the source name; an accepted input must give a
// consistent record. Anything else (crash, other exception, sanitizer report) is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/record_error.h"

namespace gm = rpsd::ground_motion;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const gm::GroundMotionRecord record = gm::parse_peer_at2(text, "fuzz.AT2");
    if (record.acceleration_m_per_s2.empty() || !(record.dt_s > 0.0) || !std::isfinite(record.dt_s) ||
        record.header_lines.size() != 4) {
      __builtin_trap();
    }
    for (const double a : record.acceleration_m_per_s2) {
      if (!std::isfinite(a)) __builtin_trap();
    }
  } catch (const rpsd::ground_motion::RecordError& e) {
    if (std::string_view(e.what()).rfind("fuzz.AT2:", 0) != 0) __builtin_trap();
  }
  return 0;
}
