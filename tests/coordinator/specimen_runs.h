// Test helper: the specimen SDOF (the seed paper's elastic SDOF: 7080 kg, 700.8 kN/m, 1.1 %)
// stepped through its planned steps without pacing, keeping every record.
#pragma once

#include <vector>

#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/specimen_sdof.h"

namespace rpsd::coordinator::testing {

struct SdofRun {
  std::vector<StepRecord> records;
  StepOutcome outcome = StepOutcome::kOk;
  LimitStop limit_stop;  // what stopped it, if a limit or a run-away did
};

inline SdofRun run_steps(const hybrid_test::TestConfig& config, hybrid_test::AssemblyOptions options = {}) {
  options.keep_records = true;
  hybrid_test::TestAssembly test(config, options);
  StepOutcome outcome = StepOutcome::kOk;
  for (std::int64_t n = 0; n < test.steps_planned() && outcome == StepOutcome::kOk; ++n) outcome = test.step();
  const LimitStop stop = test.limit_stop();
  return {test.finish(outcome).records, outcome, stop};
}

inline SdofRun run_sdof(const hybrid_test::SpecimenSdof& sdof, hybrid_test::AssemblyOptions options = {}) {
  return run_steps(hybrid_test::specimen_sdof_test(sdof), std::move(options));
}

inline std::vector<double> displacements(const SdofRun& r) {
  std::vector<double> x;
  for (const auto& s : r.records) x.push_back(s.displacement_m[0]);
  return x;
}

}  // namespace rpsd::coordinator::testing
