// The benchmark's evaluation criteria (reference sheet section 7), computed as a test runs:
// one step record at a time, so that a test of any length is evaluated without keeping its
// history. Per channel J1-J3 and the final tracking indicator; per recorded DOF J4-J9
// against the perfect-actuator reference; the energy error at the end. RMS values are raw
// (not mean-removed); J4-J9 follow the paper's order, and a floor that is an experimental
// DOF is the measured x_m there, as the paper defines it (docs/benchmark.md).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rpsd/compensation/cross_correlation_delay.h"
#include "rpsd/coordinator/step_record.h"

namespace rpsd::coordinator {

struct ChannelCriteria {
  // J1 as the benchmark defines it: the whole-sample lag in 0..49 samples (at any rate) that
  // maximises sum_k x_m(k + j) y_n(k), in ms.
  double j1_tracking_delay_ms = 0.0;
  double j2_rms_tracking_error_percent = 0.0;
  double j3_peak_tracking_error_percent = 0.0;
  double final_tracking_indicator_m2 = 0.0;
  // For the benchmark's constraints (stroke, force, velocity): the peaks of the measured
  // displacement and force, and of the command's rate of change (the measured displacement's
  // would be its sensor noise times the control rate).
  double peak_measured_m = 0.0;
  double peak_measured_force_n = 0.0;
  double peak_command_velocity_m_per_s = 0.0;
  // rpsd's own: the signed lag of measured behind target, interpolated between samples,
  // searched over +-200 ms (negative: the measurement leads), the peak nearest 0 where a
  // periodic signal has several; NaN until the record is longer than the window. At the
  // window's edge the true delay may lie beyond it.
  double tracking_delay_ms = 0.0;
  bool tracking_delay_at_window_edge = false;
};

struct DofCriteria {
  double peak_displacement_m = 0.0;
  double reference_peak_displacement_m = 0.0;
  double rms_error_percent = 0.0;   // J4-J6 for floors 1-3
  double peak_error_percent = 0.0;  // J7-J9 for floors 1-3
};

struct Criteria {
  std::vector<ChannelCriteria> channels;
  std::vector<DofCriteria> dofs;
  double energy_error_j = 0.0;  // input - (kinetic + damping + restoring) at the end
};

// Where a recorded DOF's displacement for J4-J9 comes from: the numerical model's (channel
// -1), or a channel's measured displacement divided by its displacement scale.
// A channel an experimental setup drives gives its DOF's displacement solved from the
// measured strokes (StepRecord::dof_measured_m), not its actuator's stroke.
struct FloorSource {
  int channel = -1;
  double displacement_scale = 1.0;  // specimen / model
  bool setup_dof = false;
};

class CriteriaAccumulator {
 public:
  // J1 searches 0..49 samples (NaN for 51 samples or fewer); the signed tracking delay
  // +-200 ms = +-L samples (NaN for 2 L + 2 samples or fewer).
  // `floors`: one per recorded DOF (empty: every one numerical). Not real-time safe.
  CriteriaAccumulator(int channels, int recorded_dofs, double control_rate_hz, std::vector<FloorSource> floors = {});

  // A step of the test: J1-J3, the tracking indicator and the energy. Real-time safe.
  void add_test(const StepRecord& test);
  // The same step of the test and of its reference, for J4-J9; pairs run from the first
  // step while both runs have one. Real-time safe.
  void add_pair(const StepRecord& test, const StepRecord& reference);
  // The same with the test's recorded-DOF displacements kept apart (floor_displacements).
  // Real-time safe.
  void add_pair(std::span<const double> test_displacement_m, const StepRecord& reference);
  // The recorded DOFs' displacements J4-J9 compare, model scale, into `out` (one per
  // recorded DOF). Real-time safe.
  void floor_displacements(const StepRecord& test, std::span<double> out) const;

  std::int64_t test_steps() const { return test_steps_; }
  ChannelCriteria channel(int c) const;
  Criteria criteria() const;

 private:
  struct ChannelSums {
    compensation::CrossCorrelationAccumulator j1;     // the benchmark's: 0..49 whole samples
    compensation::CrossCorrelationAccumulator delay;  // rpsd's: signed, interpolated
    double error2 = 0.0, target2 = 0.0, peak_error = 0.0, peak_target = 0.0, final_tracking_indicator_m2 = 0.0;
    double peak_measured = 0.0, peak_force = 0.0, peak_velocity = 0.0, last_command = 0.0;
  };
  struct DofSums {
    DofCriteria peaks;
    double error2 = 0.0, reference2 = 0.0, peak_error = 0.0;
  };
  int max_lag_samples_;
  double control_rate_hz_;
  std::vector<ChannelSums> channels_;
  std::vector<DofSums> dofs_;
  std::vector<FloorSource> floors_;
  std::array<double, kMaxRecordedDofs> floor_scratch_m_{};
  std::int64_t test_steps_ = 0;
  double energy_error_j_ = 0.0;
};

// J1-J3 and the final tracking indicator of one channel from kept records (target vs
// measured); the same numbers CriteriaAccumulator gives.
ChannelCriteria channel_criteria(const std::vector<StepRecord>& records, int channel, double control_rate_hz);

}  // namespace rpsd::coordinator
