// The `ground_motion:` section of a test scenario: a record file (PEER AT2, plain text or
// time/acceleration columns) or a synthetic record, scaled, trimmed, padded, baseline
// corrected on request, and resampled to the integration step.
#pragma once

#include <yaml-cpp/yaml.h>

#include "rpsd/config/source.h"
#include "rpsd/ground_motion/record.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"

namespace rpsd::scenarios {

// Reads and processes the record; a file path is relative to the section's file (and made
// absolute in the document, config::Source::relative_file). Every error names the scenario's
// key, and the record's file and line. Not real-time safe.
hybrid_test::GroundMotion read_ground_motion_section(config::Source& section, double integration_step_s);

// The section with its record replaced by `record` ({file, format, ...}) and its processing
// kept (trim, baseline correction, scaling, padding): what rpsd run --record does.
YAML::Node with_record(const YAML::Node& section, const YAML::Node& record);

}  // namespace rpsd::scenarios
