// The shipped example files several scenarios tests load, defined once: a unity build
// compiles all of scenarios_tests' files as one translation unit.
#pragma once

#include <filesystem>

#include "../servo/paper_rig.h"

namespace rpsd::scenarios {

// The bridge pier's servo node (site 1).
inline std::filesystem::path pier_node() { return testing::source_dir() / "examples/nodes/bridge-pier-site-1.yaml"; }

// The SDOF free-vibration study of the coordinator tests.
inline std::filesystem::path example() {
  return testing::source_dir() / "tests/coordinator/data/sdof-free-vibration.yaml";
}

}  // namespace rpsd::scenarios
