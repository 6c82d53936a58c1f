// The `ground_motion:` section of a test scenario: a record file (PEER AT2, plain text or
// time/acceleration columns) or a synthetic record, scaled, trimmed, padded, baseline
// corrected on request, and resampled to the integration step.
#pragma once

#include <filesystem>

#include "rpsd/config/source.h"
#include "rpsd/coordinator/test_config.h"
#include "rpsd/ground_motion/record.h"

namespace rpsd::scenarios {

// Reads and processes the record; file paths are relative to `dir`. Every error names the
// scenario's key, and the record's file and line. Not real-time safe.
coordinator::GroundMotion read_ground_motion_section(config::Source& section, const std::filesystem::path& dir,
                                                     double integration_step_s);

}  // namespace rpsd::scenarios
