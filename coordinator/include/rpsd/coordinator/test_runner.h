// Runs an `rpsd_test` scenario: builds every part from the typed scenario, runs the test as
// fast as possible, runs the same structure with a perfect actuator as the reference, and
// computes the benchmark criteria. Not real-time safe as a whole; the loop inside is.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rpsd/coordinator/rpsd_loop.h"
#include "rpsd/coordinator/test_criteria.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/scenarios/test_scenario.h"

namespace rpsd::coordinator {

class ActuatorLinks;

/// How the clock and the link behaved (real time and/or over DDS).
struct TimingReport {
  bool real_time = false;
  bool over_dds = false;
  bool memory_locked = false, fifo_granted = false, cpus_kept_awake = false;
  std::string refused;  ///< what the OS refused (mlockall, SCHED_FIFO, CPUs kept awake), once
  std::int64_t cycles = 0, overruns = 0, skipped_deadlines = 0, late_feedback = 0;
  realtime::LatencySummary jitter;  ///< wake-up lateness of the paced cycles
  struct Site {
    std::uint32_t site_id = 1;
    realtime::LatencySummary round_trip;  ///< command-to-feedback, per step
  };
  std::vector<Site> sites;
  std::vector<transport::DdsLinkCounters> dds_counters;  ///< per site, over DDS
};

struct TestRun {
  std::vector<StepRecord> records;  ///< every step, when the run kept them
  std::int64_t steps = 0;           ///< steps taken
  StepOutcome outcome = StepOutcome::kOk;
  std::int64_t steps_planned = 0;
  std::uint64_t dropped_records = 0;
  std::int64_t feedback_age_periods = 0;  ///< how old the newest feedback was when it stopped (periods)
  LimitStop limit_stop;                   ///< the coordinator limit that stopped it, if one did
  TimingReport timing;
};

/// One run of a scenario with every part built and started at rest: the numerical model,
/// partition, integrator, compensators, the actuators (simulated nodes in this process or
/// DDS links to servo nodes), the loop and its recorder. Building is not real-time safe.
class TestAssembly {
 public:
  /// `csv` receives every step as it happens (empty: none). With `perfect_actuator` the plant
  /// is replaced by one that follows its command exactly and the compensation is switched off.
  /// `keep_records`: keep every record in memory for finish(). The scenario must outlive the
  /// assembly (the loop reads its ground motion in place).
  TestAssembly(const scenarios::TestScenario& scenario, const std::filesystem::path& csv, bool perfect_actuator,
               bool keep_records);
  ~TestAssembly();
  TestAssembly(const TestAssembly&) = delete;
  TestAssembly& operator=(const TestAssembly&) = delete;

  /// Steps in the scenario (its duration, or the record's length if shorter).
  std::int64_t steps_planned() const;
  /// The test is paced by the real-time clock (the reference never is).
  bool real_time() const;
  /// One step as fast as possible, recorded. Real-time safe.
  StepOutcome step();
  const StepRecord& last_record() const;
  /// Every planned step: as fast as possible, or paced at the control rate in real time.
  /// `after_step` (optional) sees each step's record; in real time it runs inside the cycle
  /// and must be real-time safe. `progress` as for run_test (as fast as possible only).
  StepOutcome run(const std::function<void(const StepRecord&)>& after_step,
                  const std::function<void(std::int64_t, std::int64_t)>& progress);
  /// Stops the recorder; the run's outcome, counts, timing and (if kept) records. Not
  /// real-time safe.
  TestRun finish(StepOutcome outcome);

  /// The parts, for analyses beside the run (the dry run). Not real-time safe.
  const substructure::NumericalModel& numerical() const;
  const substructure::Partition& partition() const;
  const ActuatorLinks& actuators() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

/// Runs the scenario, keeping every record in memory; `csv` as for TestAssembly. `progress`
/// (optional) is called about every 0.5 s of simulated time with (steps done, steps planned).
TestRun run_test(const scenarios::TestScenario& scenario, const std::filesystem::path& csv, bool perfect_actuator,
                 const std::function<void(std::int64_t, std::int64_t)>& progress = {});

/// A test and its perfect-actuator reference, and the criteria between them.
struct EvaluatedTest {
  TestRun test;       ///< without records
  TestRun reference;  ///< without records
  Criteria criteria;
};

/// Runs the test and its reference and computes the criteria as they run, keeping no step
/// records. As fast as possible the two run side by side, step for step, so memory stays flat
/// however long the record. In real time the reference is not run inside the paced cycle: the
/// test keeps only its recorded DOFs' displacements (8 bytes per DOF per step, allocated
/// before the clock starts) and the reference runs afterwards. The reference goes on to the
/// end when the test aborts. CSVs as for TestAssembly.
EvaluatedTest run_test_and_reference(const scenarios::TestScenario& scenario, const std::filesystem::path& test_csv,
                                     const std::filesystem::path& reference_csv,
                                     const std::function<void(std::int64_t, std::int64_t)>& progress = {});

/// The criteria from two runs that kept their records; the same numbers as
/// run_test_and_reference gives.
Criteria evaluate(const scenarios::TestScenario& scenario, const TestRun& test, const TestRun& reference);

}  // namespace rpsd::coordinator
