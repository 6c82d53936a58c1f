// The paper's rig as the repository ships it, for tests.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include "rpsd/scenarios/servo_parameters_file.h"

namespace rpsd::testing {

inline std::filesystem::path source_dir() {
  const char* dir = std::getenv("RPSD_SOURCE_DIR");
  return dir ? std::filesystem::path(dir) : std::filesystem::path(RPSD_TEST_SOURCE_DIR);
}

inline servo::ServoSystemParameters paper_rig() {
  return scenarios::load_servo_parameters(source_dir() / "examples/servo/paper-mts-244.yaml");
}

}  // namespace rpsd::testing
