// The keys of the `ground_motion:` section, read apart from the record they describe: the
// section reader (ground_motion_section.cpp) reads them and then loads and processes the
// record, and the scenario reference lists them by running each on a config::KeyTable.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/processing.h"
#include "rpsd/ground_motion/synthetic.h"
#include "rpsd/ground_motion/text_readers.h"

namespace rpsd::scenarios::ground_motion_keys {

inline constexpr std::array<std::string_view, 3> kFormats = {"peer_at2", "plain_text", "time_acceleration"};

// `file:` (made absolute, see config::Source::relative_file) and `format:`, the format's own
// keys after them.
struct RecordFile {
  std::filesystem::path path;
  std::string format;
};
RecordFile record_file(config::Source& r);
ground_motion::At2ReadOptions peer_at2(config::Source& r);
ground_motion::PlainTextOptions plain_text(config::Source& r);
ground_motion::TimeAccelerationOptions time_acceleration(config::Source& r);

// `synthetic:` instead of a file (nullopt: a file).
std::optional<ground_motion::SyntheticGroundMotionOptions> synthetic(config::Source& r);

// What is done to the record, in this order: trim, baseline, scale, pad.
struct Processing {
  std::optional<ground_motion::TrimOptions> trim;
  std::optional<ground_motion::BaselineMethod> baseline;
  std::optional<double> scale_factor;
  std::optional<double> target_pga_g;
  double pad_after_s = 0.0;
};
Processing processing(config::Source& r);

}  // namespace rpsd::scenarios::ground_motion_keys
