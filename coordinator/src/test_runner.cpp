#include "rpsd/coordinator/test_runner.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "rpsd/compensation/cross_correlation_delay.h"
#include "rpsd/coordinator/actuator_links.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/substructure/ground_motion_load.h"

namespace rpsd::coordinator {
namespace {

std::unique_ptr<substructure::NumericalModel> make_numerical(const scenarios::TestScenario& s) {
  return std::visit(
      [](const auto& config) -> std::unique_ptr<substructure::NumericalModel> {
        using C = std::decay_t<decltype(config)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofConfig>) {
          auto model = std::make_unique<substructure::LinearMdofModel>();
          model->configure(config);
          return model;
        } else {
          auto model = std::make_unique<substructure::ShearBuilding>();
          model->configure(config);
          return model;
        }
      },
      s.structure);
}

integrators::StructuralMatrices integrator_matrices(const substructure::NumericalModel& model,
                                                    const substructure::StructuralMatrix& k0) {
  if (model.mass().is_sparse() || k0.is_sparse()) {
    return integrators::SparseStructuralMatrices{model.mass().to_sparse(), model.damping().to_sparse(), k0.to_sparse()};
  }
  return integrators::DenseStructuralMatrices{model.mass().to_dense(), model.damping().to_dense(), k0.to_dense()};
}

// The paced loop: absolute deadlines at the integration step; each cycle may wait for its
// feedback until a fraction of the period is left for the integrator and the recorder.
TimingReport run_paced(RpsdLoop& loop, Recorder& recorder, ActuatorLinks& actuators, const scenarios::TestScenario& s,
                       TestRun& run) {
  TimingReport timing;
  timing.real_time = true;
  const realtime::RealTimeSetupReport granted = realtime::apply_realtime(s.clock.realtime);
  timing.memory_locked = granted.memory_locked;
  timing.fifo_granted = granted.fifo_granted;
  timing.refused = granted.refused;
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / s.control_rate_hz));
  realtime::Pacer pacer(period_ns);
  realtime::LatencyHistogram jitter;
  // The first exchange may wait the full feedback timeout (the link's first sample, page
  // faults after mlockall); the clock starts once it is done.
  if (run.steps_planned > 0) {
    actuators.set_receive_deadline_ns(0);
    run.outcome = loop.step(recorder);
    if (run.outcome != StepOutcome::kOk) return timing;
  }
  pacer.start();
  for (std::int64_t n = 1; n < run.steps_planned; ++n) {
    const std::int64_t late_ns = pacer.wait_next();
    jitter.add(late_ns);
    loop.set_cycle_lateness_ns(late_ns);
    actuators.set_receive_deadline_ns(pacer.current_deadline_ns() + period_ns * 8 / 10);
    run.outcome = loop.step(recorder);
    if (run.outcome != StepOutcome::kOk) break;
  }
  timing.cycles = pacer.cycles();
  timing.overruns = pacer.overruns();
  timing.skipped_deadlines = pacer.skipped_deadlines();
  timing.jitter = jitter.summary();
  timing.late_feedback = loop.late_feedback_total();
  return timing;
}

// Command-to-feedback latency per site from the records (each site's first channel).
void fill_latency(TestRun& run, const ActuatorLinks& actuators) {
  for (const SiteSummary& site : actuators.sites()) {
    realtime::LatencyHistogram h;
    const int ch = site.channels.front();
    for (const StepRecord& r : run.records) h.add(static_cast<std::int64_t>(std::llround(r.round_trip_s[ch] * 1e9)));
    run.timing.sites.push_back({site.site_id, h.summary()});
  }
  run.timing.over_dds = actuators.over_dds();
  if (actuators.over_dds()) run.timing.dds_counters = actuators.dds_counters();
}

}  // namespace

TestRun run_test(const scenarios::TestScenario& s, const std::filesystem::path& csv, bool perfect_actuator,
                 const std::function<void(std::int64_t, std::int64_t)>& progress) {
  auto numerical = make_numerical(s);
  const Eigen::Index dofs = numerical->dofs();
  const int channels = static_cast<int>(s.experimental.size());

  substructure::Partition partition;
  substructure::PartitionConfig split;
  split.dofs = dofs;
  for (const auto& e : s.experimental) split.experimental.push_back(e.dof);
  split.influence = s.influence;
  partition.configure(split);

  auto integrator = integrators::make_integrator(s.integrator);
  const double dt_s = 1.0 / s.control_rate_hz;
  integrator->configure(integrator_matrices(*numerical, partition.with_specimen_stiffness(numerical->initial_stiffness())),
                        dt_s);
  const double control_period_s = dt_s / integrator->iterations_per_step();

  std::vector<std::unique_ptr<compensation::CommandCompensator>> compensators;
  LoopParts parts;
  parts.compensators.resize(static_cast<std::size_t>(channels));
  parts.force_paths.resize(static_cast<std::size_t>(channels));
  for (const auto& channel : s.experimental) {
    // The loop wants channel order; the partition numbered the channels 0..n-1.
    const auto ch = static_cast<std::size_t>(channel.dof.actuator_channel);
    compensators.push_back(compensation::make_compensator(
        perfect_actuator ? compensation::CompensatorConfig{compensation::PassThroughParameters{}} : s.compensation,
        control_period_s));
    parts.compensators[ch] = compensators.back().get();
    parts.force_paths[ch] = {channel.restoring_force == scenarios::RestoringForceSource::kMeasuredForce
                                 ? RestoringForcePath::Kind::kMeasuredForce
                                 : RestoringForcePath::Kind::kStiffnessTimesMeasuredDisplacement,
                             channel.dof.specimen_stiffness_estimate_n_per_m};
  }

  // Start at rest at the initial displacement, the specimens holding it.
  Eigen::VectorXd hold(channels);
  partition.extract_commands(s.initial_displacement_m, hold);
  ActuatorLinks actuators(s, control_period_s, perfect_actuator,
                          std::span<const double>(hold.data(), static_cast<std::size_t>(channels)));

  substructure::GroundMotionLoad ground_load;
  parts.integrator = integrator.get();
  parts.numerical = numerical.get();
  parts.partition = &partition;
  parts.link = &actuators.link();
  parts.recorded_dofs = s.record_dofs;
  parts.test_id = s.transport.test_id;
  const bool real_time = s.clock.mode == scenarios::ClockConfig::Mode::kRealTime && !perfect_actuator;
  parts.wait_for_recorder = !real_time;
  parts.max_late_feedback = real_time ? s.clock.max_late_feedback : 0;
  if (s.ground_motion) {
    ground_load.configure(numerical->mass(), s.influence);
    parts.ground_acceleration_m_per_s2 = s.ground_motion->acceleration_m_per_s2;
    parts.ground_load = &ground_load;
  }
  RpsdLoop loop(parts);
  std::vector<double> force0(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    force0[static_cast<std::size_t>(c)] = parts.force_paths[static_cast<std::size_t>(c)].kind == RestoringForcePath::Kind::kMeasuredForce
                                              ? actuators.initial_force_n(c)
                                              : parts.force_paths[static_cast<std::size_t>(c)].stiffness_n_per_m * hold[c];
  }
  loop.start(s.initial_displacement_m, force0);

  TestRun run;
  run.steps_planned = static_cast<std::int64_t>(std::llround(s.duration_s * s.control_rate_hz));
  if (loop.steps_available() >= 0) run.steps_planned = std::min(run.steps_planned, loop.steps_available());
  Recorder recorder(csv, channels, static_cast<int>(s.record_dofs.size()));
  const auto report_every = std::max<std::int64_t>(1, static_cast<std::int64_t>(0.5 * s.control_rate_hz));
  if (real_time) {
    run.timing = run_paced(loop, recorder, actuators, s, run);
  } else {
    for (std::int64_t n = 0; n < run.steps_planned; ++n) {
      run.outcome = loop.step(recorder);
      if (run.outcome != StepOutcome::kOk) break;
      if (progress && (n + 1) % report_every == 0) progress(n + 1, run.steps_planned);
    }
  }
  run.late_feedback_in_a_row = loop.late_feedback_in_a_row();
  run.dropped_records = recorder.dropped();
  run.records = recorder.finish();
  fill_latency(run, actuators);
  return run;
}

ChannelCriteria channel_criteria(const std::vector<StepRecord>& records, int c, double control_rate_hz) {
  std::vector<double> target, measured;
  double error2 = 0.0, target2 = 0.0, peak_error = 0.0, peak_target = 0.0;
  for (const auto& r : records) {
    target.push_back(r.target_m[c]);
    measured.push_back(r.measured_m[c]);
    const double e = r.measured_m[c] - r.target_m[c];
    error2 += e * e;
    target2 += r.target_m[c] * r.target_m[c];
    peak_error = std::max(peak_error, std::abs(e));
    peak_target = std::max(peak_target, std::abs(r.target_m[c]));
  }
  ChannelCriteria cc;
  compensation::CrossCorrelationOptions options;
  options.max_lag_samples = static_cast<int>(0.2 * control_rate_hz);  // up to 200 ms
  cc.j1_tracking_delay_ms = std::nan("");
  if (target.size() > static_cast<std::size_t>(2 * options.max_lag_samples)) {
    const auto j1 = compensation::cross_correlation_delay(target, measured, options);
    if (j1.valid) cc.j1_tracking_delay_ms = 1e3 * j1.delay_samples / control_rate_hz;
  }
  cc.j2_rms_tracking_error_percent = target2 > 0.0 ? 100.0 * std::sqrt(error2 / target2) : 0.0;
  cc.j3_peak_tracking_error_percent = peak_target > 0.0 ? 100.0 * peak_error / peak_target : 0.0;
  cc.final_tracking_indicator_m2 = records.empty() ? 0.0 : records.back().tracking_indicator_m2[c];
  return cc;
}

Criteria evaluate(const scenarios::TestScenario& s, const TestRun& test, const TestRun& reference) {
  Criteria criteria;
  for (int c = 0; c < static_cast<int>(s.experimental.size()); ++c) {
    criteria.channels.push_back(channel_criteria(test.records, c, s.control_rate_hz));
  }
  const std::size_t n = std::min(test.records.size(), reference.records.size());
  for (std::size_t d = 0; d < s.record_dofs.size(); ++d) {
    DofCriteria dc;
    double error2 = 0.0, reference2 = 0.0, peak_error = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = test.records[i].displacement_m[d], xr = reference.records[i].displacement_m[d];
      error2 += (x - xr) * (x - xr);
      reference2 += xr * xr;
      peak_error = std::max(peak_error, std::abs(x - xr));
      dc.peak_displacement_m = std::max(dc.peak_displacement_m, std::abs(x));
      dc.reference_peak_displacement_m = std::max(dc.reference_peak_displacement_m, std::abs(xr));
    }
    dc.rms_error_percent = reference2 > 0.0 ? 100.0 * std::sqrt(error2 / reference2) : 0.0;
    dc.peak_error_percent = dc.reference_peak_displacement_m > 0.0 ? 100.0 * peak_error / dc.reference_peak_displacement_m : 0.0;
    criteria.dofs.push_back(dc);
  }
  if (!test.records.empty()) {
    const auto& last = test.records.back();
    criteria.energy_error_j = last.input_energy_j - (last.kinetic_energy_j + last.damping_energy_j + last.restoring_energy_j);
  }
  return criteria;
}

}  // namespace rpsd::coordinator
