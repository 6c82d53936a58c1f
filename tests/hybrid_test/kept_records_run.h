// A whole run through the assembly, every record kept and no CSV written, defined once: a unity
// build compiles all of hybrid_test_tests' files as one translation unit.
#pragma once

#include "rpsd/hybrid_test/hybrid_test_assembly.h"

namespace rpsd::hybrid_test {

inline TestRun run_keeping_records(const TestConfig& t) {
  TestAssembly assembly(t, {{}, false, true, {}});
  return assembly.finish(assembly.run({}, {}));
}

}  // namespace rpsd::hybrid_test
