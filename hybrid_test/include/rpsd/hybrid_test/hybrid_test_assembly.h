// One test built from its typed configuration: the numerical model, partition, integrator,
// compensators, the actuators (a lock-step servo node per site in this process, or DDS links
// to the sites' `rpsd servo-node`s), the loop and its recorder. Building is not real-time
// safe; stepping is.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rpsd/coordinator/live_counters.h"
#include "rpsd/coordinator/record_observer.h"
#include "rpsd/coordinator/recorder.h"
#include "rpsd/coordinator/rpsd_loop.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/hybrid_test/setup_plan.h"
#include "rpsd/operator_commands/operator_command_handler.h"
#include "rpsd/operator_commands/operator_control.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/transport/dds_link.h"

namespace rpsd::hybrid_test {

class ActuatorLinks;

// How the clock and the link behaved (real time and/or over DDS).
struct TimingReport {
  bool real_time = false;
  bool over_dds = false;
  bool memory_locked = false, fifo_granted = false, cpus_kept_awake = false;
  int pinned_cpu = -1;  // clock.loop_cpu, when asked and granted
  std::string refused;  // what the OS refused (mlockall, SCHED_FIFO, CPUs kept awake), once
  std::int64_t cycles = 0, overruns = 0, skipped_deadlines = 0, late_feedback = 0;
  realtime::LatencySummary jitter;  // wake-up lateness of the paced cycles
  struct Site {
    std::uint32_t site_id = 1;
    realtime::LatencySummary round_trip;  // command-to-feedback, per step
  };
  std::vector<Site> sites;
  std::vector<transport::DdsLinkCounters> dds_counters;  // per site, over DDS
};

// An interval an operator held a lock-step test (operator_commands/): no step was taken, the
// actuators held their last command.
struct HeldInterval {
  std::int64_t after_step = 0;      // steps taken when the hold began; the next one taken after it
  std::int64_t start_unix_ns = 0;   // wall clock
  std::int64_t end_unix_ns = 0;     // 0: still held when the run ended (stopped while held)
  std::string held_by, resumed_by;  // senders, as they name themselves
};

// An operator's stop with operator_commands.return_to_start: every channel's target ramped
// from where the stop left it to its start position at the stated velocity, one exchange per
// control period. Rows: time_s, then per channel target, command, measured displacement and
// measured force.
struct ReturnToStart {
  bool asked = false;
  double velocity_m_per_s = 0.0;
  int channels = 0;
  std::int64_t exchanges = 0;
  std::vector<double> rows;                                          // exchanges x (1 + 4 channels)
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;  // kOk: reached the start
  coordinator::LimitStop limit_stop;                                 // what stopped it, if anything
};

struct TestRun {
  std::vector<coordinator::StepRecord> records;  // every step, when the run kept them
  std::int64_t steps = 0;                        // steps taken
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
  std::int64_t steps_planned = 0;
  std::uint64_t dropped_records = 0;
  std::string write_error;                // kResultsNotWritten: the file and the system's reason
  std::int64_t feedback_age_periods = 0;  // how old the newest feedback was when it stopped (periods)
  coordinator::LimitStop limit_stop;      // the coordinator limit that stopped it, if one did
  std::uint64_t run_id = 0;               // this run's identity on every command
  std::string refusal;                    // coordinator::StepOutcome::kRefused: which site refused the run and why
  std::string node_fault;                 // kNodeFault: what the faulted nodes say faulted them ("site 1: ...")
  // kHostCallFailed: which host part failed in which call, in the host's words
  // ("compensation external `pid` (channel 0) command(): ...").
  std::string host_error;
  TimingReport timing;
  // Per experimental setup: each actuator's reading at the start, the stroke the geometry
  // predicted there and the offset used for every command and measurement.
  std::vector<SetupCalibration> calibrations;
  // The held forces as the loop held them (their channel, limits and force at rest); none for
  // the perfect-actuator reference.
  std::vector<coordinator::HeldForceChannel> held_forces;
  std::vector<HeldForceStats> held_stats;  // per held force, from every step's record
  // Operator commands (operator_commands/): the held intervals, who stopped or aborted the run
  // (kOperatorStop, kOperatorAbort), the return to the start positions, and every command heard.
  std::vector<HeldInterval> held;
  std::string operator_sender;
  ReturnToStart return_to_start;
  std::vector<operator_commands::OperatorCommandEvent> operator_commands;
};

struct AssemblyOptions {
  std::filesystem::path csv;  // receives every step as it happens (empty: none)
  // The reference: every plant follows its command exactly, compensation and limits off.
  bool perfect_actuator = false;
  bool keep_records = false;  // keep every record in memory for finish()
  // Optional: a link placed between the loop and the actuators (a network emulation that
  // delays or loses feedback, for tests).
  std::function<std::unique_ptr<transport::Link>(transport::Link& actuators)> wrap_link;
  // Set (from a signal handler, another thread) when the user asks the run to stop: the
  // step under way finishes and is recorded, the next one returns kInterrupted.
  const std::atomic<bool>* stop_request = nullptr;
  // Watchers of every record, called by the recorder's writer thread (never the loop's): the
  // telemetry, the terminal's progress. They must outlive finish().
  std::vector<coordinator::RecordObserver*> record_observers = {};
  // Set by the run's operator-command listener: polled between steps (one atomic load); a
  // stop ends the run in order (kOperatorStop, with the return to start when the scenario asks
  // for it), an abort at once (kOperatorAbort), a hold (lock-step only) waits between steps.
  operator_commands::OperatorControl* operator_control = nullptr;
};

// The columns a test's recorder writes beyond its channels and DOFs (RecorderOptions: the DOF
// view of the channels a setup drives, the held forces' link channels: none in the
// perfect-actuator reference, which holds no force), for whoever else writes its records
// (results.h5). Not real-time safe.
coordinator::RecorderOptions recorded_columns(const TestConfig& config, bool perfect_actuator);

// One run of a test with every part built and started at rest.
class TestAssembly {
 public:
  // The configuration must outlive the assembly (the loop reads its ground motion in place).
  TestAssembly(const TestConfig& config, const AssemblyOptions& options);
  ~TestAssembly();
  TestAssembly(const TestAssembly&) = delete;
  TestAssembly& operator=(const TestAssembly&) = delete;

  // This run's identity, on every command: no other run carries it.
  std::uint64_t run_id() const;
  // What the run has done so far, updated by the loop's thread (relaxed), for other threads.
  const coordinator::LiveCounters& live_counters() const;
  // Steps in the scenario (its duration, or the record's length if shorter).
  std::int64_t steps_planned() const;
  // The test is paced by the real-time clock (the reference never is).
  bool real_time() const;
  // The integration step over the integrator's iterations per step.
  double control_period_s() const;
  // Steps between two progress reports: about 0.5 s of simulated time.
  std::int64_t progress_every_steps() const;
  // One step as fast as possible, recorded (a full recorder queue makes it wait, so nothing
  // is lost); kRefused without a step when a site's node refused the run at the start.
  // Real-time safe except for that wait.
  coordinator::StepOutcome step();
  const coordinator::StepRecord& last_record() const;
  // What stopped the loop when step() or run() returned kLimit or kRunAway.
  const coordinator::LimitStop& limit_stop() const;
  // Every planned step: as fast as possible, or paced at the control rate in real time.
  // `after_step` (optional) sees each step's record; in real time it runs inside the cycle
  // and must be real-time safe. `progress` as for run_test (as fast as possible only).
  coordinator::StepOutcome run(const std::function<void(const coordinator::StepRecord&)>& after_step,
                               const std::function<void(std::int64_t, std::int64_t)>& progress);
  // Stops the recorder and ends the run on the sites' nodes; the run's outcome, counts, timing
  // and (if kept) records. Not real-time safe.
  TestRun finish(coordinator::StepOutcome outcome);

  // The parts, for analyses beside the run (the dry run). Not real-time safe.
  const substructure::NumericalModel& numerical() const;
  const substructure::Partition& partition() const;
  const ActuatorLinks& actuators() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace rpsd::hybrid_test
