// Runs an `rpsd_test` scenario: builds every part from the typed scenario, runs the test as
// fast as possible, runs the same structure again with a perfect actuator as the reference,
// and computes the benchmark criteria. Not real-time safe as a whole; the loop inside is.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rpsd/coordinator/rpsd_loop.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/scenarios/test_scenario.h"

namespace rpsd::coordinator {

/// How the clock and the link behaved (real time and/or over DDS).
struct TimingReport {
  bool real_time = false;
  bool over_dds = false;
  bool memory_locked = false, fifo_granted = false;
  std::string refused;  ///< what the OS refused (mlockall, SCHED_FIFO), once
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
  std::vector<StepRecord> records;
  StepOutcome outcome = StepOutcome::kOk;
  std::int64_t steps_planned = 0;
  std::uint64_t dropped_records = 0;
  int late_feedback_in_a_row = 0;  ///< periods without fresh feedback when it stopped
  TimingReport timing;
};

/// Runs the scenario; `csv` receives every step as it happens (empty: memory only). With
/// `perfect_actuator` the plant is replaced by one that follows its command exactly and the
/// compensation is switched off. `progress` (optional) is called about every 0.5 s of
/// simulated time with (steps done, steps planned).
TestRun run_test(const scenarios::TestScenario& scenario, const std::filesystem::path& csv, bool perfect_actuator,
                 const std::function<void(std::int64_t, std::int64_t)>& progress = {});

/// The benchmark's evaluation criteria (reference sheet section 7), per channel and per
/// recorded DOF. RMS values are raw (not mean-removed); J4-J9 follow the paper's order.
struct ChannelCriteria {
  double j1_tracking_delay_ms = 0.0;   ///< cross-correlation lag of measured behind target
  double j2_rms_tracking_error_percent = 0.0;
  double j3_peak_tracking_error_percent = 0.0;
  double final_tracking_indicator_m2 = 0.0;
};
/// J1-J3 and the final tracking indicator of one channel from its records (target vs
/// measured); J1 searches lags up to 200 ms and is NaN when the record is too short.
ChannelCriteria channel_criteria(const std::vector<StepRecord>& records, int channel, double control_rate_hz);

struct DofCriteria {
  double peak_displacement_m = 0.0;
  double reference_peak_displacement_m = 0.0;
  double rms_error_percent = 0.0;   ///< J4-J6 for floors 1-3
  double peak_error_percent = 0.0;  ///< J7-J9 for floors 1-3
};
struct Criteria {
  std::vector<ChannelCriteria> channels;
  std::vector<DofCriteria> dofs;
  double energy_error_j = 0.0;  ///< input - (kinetic + damping + restoring) at the end
};

Criteria evaluate(const scenarios::TestScenario& scenario, const TestRun& test, const TestRun& reference);

}  // namespace rpsd::coordinator
