// The shipped El Centro SDOF study, loaded once, as the recorder tests run it; defined once:
// a unity build compiles all of coordinator_tests' files as one translation unit.
#pragma once

#include <variant>

#include "../servo/paper_rig.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {

inline const hybrid_test::TestConfig& elcentro() {
  static const auto file = scenarios::load_study(rpsd::testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml");
  return std::get<hybrid_test::TestConfig>(file.study);
}

}  // namespace rpsd::coordinator
