// What a test file says, typed (scenarios/ reads it): a whole test (TestConfig) with, at most,
// a sweep over one or two of its keys or a Monte Carlo batch drawn about them. The test output
// (hybrid_test_output.h, monte_carlo_output.h) needs only this; studies/ adds the paper's studies.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_config.h"

namespace rpsd::hybrid_test {

// One swept key of an `rpsd_test` scenario and the values it takes (as YAML scalars).
struct SweepAxis {
  std::string key_path;
  std::vector<double> values;
};

// `monte_carlo:` of an rpsd_test scenario: each run is the scenario with the named keys drawn
// about their values in the file (monte_carlo.h).
struct MonteCarloParameter {
  enum class Distribution { kNormal, kUniform };
  std::string key_path;
  Distribution distribution = Distribution::kNormal;
  double nominal = 0.0;  // the scenario's own value
  double spread = 0.0;   // standard deviation (normal) or half width (uniform), > 0
  // Further keys that take the same drawn value in each run (one property stated in two
  // places, e.g. the specimen's k_e in the partition and in the plant); the file gives each
  // the key's own value.
  std::vector<std::string> also_key_paths;
};
struct MonteCarloConfig {
  int runs = 0;
  std::uint64_t seed = 0;
  std::vector<MonteCarloParameter> parameters;
  std::string noise_seed_key;  // optional: each run gets its own seed there (seed + run number)
};

// Everything of a study file but which study it is (studies::StudyDocument adds that).
struct TestDocument {
  std::string name;            // the file's stem, for titles
  std::string description;     // optional `description:` text
  std::string effective_yaml;  // the document as read, with --set overrides applied
  // Every file read to build it, in the order read: the scenario, parameter files, records,
  // matrices (for the SHA-256 of each in summary.json).
  std::vector<std::filesystem::path> input_files;
  // `sweep:` of an rpsd_test scenario (one or two axes; empty when there is none). Every
  // case has been read and checked before anything runs.
  std::vector<SweepAxis> sweep;
  std::vector<TestConfig> sweep_cases;            // the first axis varies fastest
  std::vector<std::vector<double>> sweep_values;  // the axis values of each case
  std::vector<std::string> case_yaml;             // each case's own document (its effective-scenario.yaml)
  // `monte_carlo:` (then sweep is empty, sweep_cases are the runs and sweep_values the drawn
  // parameter values of each).
  std::optional<MonteCarloConfig> monte_carlo;
};

}  // namespace rpsd::hybrid_test
