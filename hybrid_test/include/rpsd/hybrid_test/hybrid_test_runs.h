// Whole runs of a test: on its own, or with its perfect-actuator reference beside it and the
// benchmark's criteria between them. Not real-time safe as a whole; the loop inside is.
#pragma once

#include <filesystem>
#include <functional>
#include <vector>

#include "rpsd/coordinator/run_criteria.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/operator_listener.h"

namespace rpsd::hybrid_test {

// (steps done, steps planned), about every 0.5 s of simulated time.
using Progress = std::function<void(std::int64_t, std::int64_t)>;

// Runs the test, keeping every record in memory; `csv` as in AssemblyOptions.
TestRun run_test(const TestConfig& config, const std::filesystem::path& csv, bool perfect_actuator,
                 const Progress& progress = {});

// Who watches the test (not its reference) as it runs, off the loop's thread: observers of its
// records (the recorder's writer thread) and `started`, called with the built test before its
// first step on the calling thread (run_watchers.h).
struct RunWatch {
  std::vector<coordinator::RecordObserver*> observers;
  // Observers of the reference's records (its recorder's writer thread): results.h5.
  std::vector<coordinator::RecordObserver*> reference_observers;
  std::function<void(const TestAssembly&)> started;
  // Told each operator command the run's listener heard (operator_listener.h), off the loop.
  OperatorCommandHook on_operator_command;
};

// A test and its perfect-actuator reference, and the criteria between them.
struct EvaluatedTest {
  TestRun test;       // without records
  TestRun reference;  // without records
  coordinator::Criteria criteria;
};

// Runs the test and its reference and computes the criteria as they run, keeping no step
// records. As fast as possible the two run side by side, step for step, so memory stays flat
// however long the record. In real time the reference is not run inside the paced cycle: the
// test keeps only its recorded DOFs' displacements (8 bytes per DOF per step, allocated
// before the clock starts) and the reference runs afterwards. The reference goes on to the
// end when the test aborts. Both stop when *stop_request is set (AssemblyOptions). The test
// hears operator commands as listen_for_operators says (the reference never does);
// `on_operator_command` sees each one heard.
EvaluatedTest run_test_and_reference(const TestConfig& config, const std::filesystem::path& test_csv,
                                     const std::filesystem::path& reference_csv, const Progress& progress = {},
                                     const std::atomic<bool>* stop_request = nullptr, const RunWatch& watch = {});

// The criteria from two runs that kept their records; the same numbers as
// run_test_and_reference gives.
coordinator::Criteria evaluate(const TestConfig& config, const TestRun& test, const TestRun& reference);

}  // namespace rpsd::hybrid_test
