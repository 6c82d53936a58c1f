// Reads an `rpsd_test` scenario. Every error names the file, line, column and key path.
#pragma once

#include <filesystem>

#include "rpsd/hybrid_test/external_parts.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {

// Reads the scenario from the document `root` of `file` (paths inside are relative to it).
// A compensator or structure of kind external takes its source from `external` (the host
// program's), refused at its name when there is none and at its kind under a real-time clock.
// Not real-time safe.
hybrid_test::TestConfig read_test_config(MappingReader& root, const std::filesystem::path& file,
                                         const hybrid_test::ExternalParts& external = {});

}  // namespace rpsd::scenarios
