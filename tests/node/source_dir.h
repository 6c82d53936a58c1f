// The repository's root as the node tests find it (RPSD_SOURCE_DIR, else the configured one),
// defined once: a unity build compiles all of node_tests' files as one translation unit.
#pragma once

#include <cstdlib>
#include <filesystem>

namespace rpsd::node {

inline std::filesystem::path source_dir() {
  if (const char* env = std::getenv("RPSD_SOURCE_DIR"); env != nullptr && *env != '\0') return env;
  return RPSD_TEST_SOURCE_DIR;
}

}  // namespace rpsd::node
