#include "rpsd/coordinator/run_criteria.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace rpsd::coordinator {
namespace {

// The benchmark's J1: lags 0..49 whole samples, the released code's definition, kept in
// samples at any control rate (docs/benchmark.md).
constexpr int kBenchmarkJ1MaxLagSamples = 49;

compensation::CrossCorrelationOptions j1_options() {
  compensation::CrossCorrelationOptions options;
  options.max_lag_samples = kBenchmarkJ1MaxLagSamples;
  options.subsample_refinement = false;
  return options;
}

// rpsd's signed delay: +-max_lag_samples, refined between samples.
compensation::CrossCorrelationOptions signed_delay_options(int max_lag_samples) {
  compensation::CrossCorrelationOptions options;
  options.max_lag_samples = max_lag_samples;
  options.min_lag_samples = -max_lag_samples;
  return options;
}

}  // namespace

CriteriaAccumulator::CriteriaAccumulator(int channels, int recorded_dofs, double control_rate_hz,
                                         std::vector<FloorSource> floors)
    : max_lag_samples_(std::max(1, static_cast<int>(0.2 * control_rate_hz))),  // +-200 ms
      control_rate_hz_(control_rate_hz),
      dofs_(static_cast<std::size_t>(recorded_dofs)),
      floors_(std::move(floors)) {
  if (recorded_dofs > kMaxRecordedDofs)
    throw std::invalid_argument("criteria: at most " + std::to_string(kMaxRecordedDofs) + " recorded DOFs");
  floors_.resize(dofs_.size());
  for (const FloorSource& f : floors_) {
    if (f.channel >= channels || !(f.displacement_scale > 0.0))
      throw std::invalid_argument("criteria: a floor's channel or displacement scale is out of range");
  }
  channels_.reserve(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c)
    channels_.push_back({compensation::CrossCorrelationAccumulator(j1_options()),
                         compensation::CrossCorrelationAccumulator(signed_delay_options(max_lag_samples_))});
}

void CriteriaAccumulator::add_test(const StepRecord& r) {
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    ChannelSums& s = channels_[c];
    const double target = r.target_m[c], measured = r.measured_m[c];
    s.j1.add(target, measured);
    s.delay.add(target, measured);
    const double e = measured - target;
    s.error2 += e * e;
    s.target2 += target * target;
    s.peak_error = std::max(s.peak_error, std::abs(e));
    s.peak_target = std::max(s.peak_target, std::abs(target));
    s.final_tracking_indicator_m2 = r.tracking_indicator_m2[c];
    s.peak_measured = std::max(s.peak_measured, std::abs(measured));
    s.peak_force = std::max(s.peak_force, std::abs(r.measured_force_n[c]));
    if (test_steps_ > 0) {
      s.peak_velocity = std::max(s.peak_velocity, std::abs(r.command_m[c] - s.last_command) * control_rate_hz_);
    }
    s.last_command = r.command_m[c];
  }
  energy_error_j_ = r.input_energy_j - (r.kinetic_energy_j + r.damping_energy_j + r.restoring_energy_j);
  ++test_steps_;
}

void CriteriaAccumulator::floor_displacements(const StepRecord& test, std::span<double> out) const {
  for (std::size_t d = 0; d < dofs_.size(); ++d) {
    const FloorSource& f = floors_[d];
    out[d] = f.channel < 0 ? test.displacement_m[d]
             : f.setup_dof ? test.dof_measured_m[f.channel] / f.displacement_scale
                           : test.measured_m[f.channel] / f.displacement_scale;
  }
}

void CriteriaAccumulator::add_pair(const StepRecord& test, const StepRecord& reference) {
  floor_displacements(test, floor_scratch_m_);
  add_pair(std::span<const double>(floor_scratch_m_.data(), dofs_.size()), reference);
}

void CriteriaAccumulator::add_pair(std::span<const double> test_displacement_m, const StepRecord& reference) {
  for (std::size_t d = 0; d < dofs_.size(); ++d) {
    DofSums& s = dofs_[d];
    const double x = test_displacement_m[d], xr = reference.displacement_m[d];
    s.error2 += (x - xr) * (x - xr);
    s.reference2 += xr * xr;
    s.peak_error = std::max(s.peak_error, std::abs(x - xr));
    s.peaks.peak_displacement_m = std::max(s.peaks.peak_displacement_m, std::abs(x));
    s.peaks.reference_peak_displacement_m = std::max(s.peaks.reference_peak_displacement_m, std::abs(xr));
  }
}

ChannelCriteria CriteriaAccumulator::channel(int c) const {
  const ChannelSums& s = channels_[static_cast<std::size_t>(c)];
  ChannelCriteria cc;
  cc.j1_tracking_delay_ms = cc.tracking_delay_ms = std::nan("");
  if (const auto j1 = s.j1.estimate(); j1.valid) cc.j1_tracking_delay_ms = 1e3 * j1.lag_samples / control_rate_hz_;
  if (const auto delay = s.delay.estimate(); delay.valid) {
    cc.tracking_delay_ms = 1e3 * delay.delay_samples / control_rate_hz_;
    cc.tracking_delay_at_window_edge = delay.at_boundary;
  }
  cc.j2_rms_tracking_error_percent = s.target2 > 0.0 ? 100.0 * std::sqrt(s.error2 / s.target2) : 0.0;
  cc.j3_peak_tracking_error_percent = s.peak_target > 0.0 ? 100.0 * s.peak_error / s.peak_target : 0.0;
  cc.final_tracking_indicator_m2 = s.final_tracking_indicator_m2;
  cc.peak_measured_m = s.peak_measured;
  cc.peak_measured_force_n = s.peak_force;
  cc.peak_command_velocity_m_per_s = s.peak_velocity;
  return cc;
}

Criteria CriteriaAccumulator::criteria() const {
  Criteria criteria;
  for (int c = 0; c < static_cast<int>(channels_.size()); ++c) criteria.channels.push_back(channel(c));
  for (const DofSums& s : dofs_) {
    DofCriteria dc = s.peaks;
    dc.rms_error_percent = s.reference2 > 0.0 ? 100.0 * std::sqrt(s.error2 / s.reference2) : 0.0;
    dc.peak_error_percent =
        dc.reference_peak_displacement_m > 0.0 ? 100.0 * s.peak_error / dc.reference_peak_displacement_m : 0.0;
    criteria.dofs.push_back(dc);
  }
  criteria.energy_error_j = energy_error_j_;
  return criteria;
}

ChannelCriteria channel_criteria(const std::vector<StepRecord>& records, int channel, double control_rate_hz) {
  CriteriaAccumulator sums(channel + 1, 0, control_rate_hz);
  for (const auto& r : records) sums.add_test(r);
  return sums.channel(channel);
}

}  // namespace rpsd::coordinator
