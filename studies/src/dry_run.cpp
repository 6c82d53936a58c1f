#include "rpsd/studies/dry_run.h"

#include "rpsd/servo/converted_plant.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "large_models.h"
#include "rpsd/compensation/cross_correlation_delay.h"
#include "rpsd/compensation/delay_theory.h"
#include "rpsd/hybrid_test/actuator_links.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/hybrid_test/setup_plan.h"
#include "rpsd/servo/linear_analysis.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_frequency_response.h"
#include "rpsd/substructure/modal.h"

namespace rpsd::studies {
namespace {

// Signed delay of measured behind target (negative: ahead), searched over +-200 ms as the
// run's summary does (coordinator/run_criteria.h), with the Pearson coefficient.
std::optional<compensation::DelayEstimate> signed_delay(const std::vector<double>& target,
                                                        const std::vector<double>& measured, double rate_hz) {
  compensation::CrossCorrelationOptions options;
  options.max_lag_samples = std::max(1, static_cast<int>(0.2 * rate_hz));
  options.min_lag_samples = -options.max_lag_samples;
  options.measure = compensation::CorrelationMeasure::kPearson;
  if (static_cast<int>(target.size()) <= 2 * options.max_lag_samples + 2) return std::nullopt;
  const auto delay = compensation::cross_correlation_delay(target, measured, options);
  if (!delay.valid) return std::nullopt;
  return delay;
}

// The compensator and the simulated plant in series, seen as one plant: what the specimen
// gets for a target, one control period per advance (as the loop drives them).
class CompensatedPlant final : public servo::Plant {
 public:
  CompensatedPlant(const hybrid_test::TestConfig& s)
      : plant_(servo::make_plant(s.plant)),
        compensator_(compensation::make_compensator(s.compensation, 1.0 / s.control_rate_hz)) {}
  void reset(double displacement_m) override {
    plant_->reset(displacement_m);
    compensator_->reset(displacement_m);
    command_m_ = displacement_m;
  }
  void advance(double, double target_m, double duration_s) override {
    const double command_m = compensator_->command(target_m);
    plant_->advance(command_m_, command_m, duration_s);
    command_m_ = command_m;
    compensator_->observe(target_m, plant_->measure().displacement_m);
  }
  servo::PlantMeasurement measure() const override { return plant_->measure(); }

 private:
  std::unique_ptr<servo::Plant> plant_;
  std::unique_ptr<compensation::CommandCompensator> compensator_;
  double command_m_ = 0.0;
};

// Gain and equivalent delay -phase / w (negative: a lead) of compensator and plant at w,
// measured by a sine test as a lab would (settled, fitted).
struct LoopResponse {
  double gain = 1.0, delay_s = 0.0;
};
LoopResponse compensated_plant_response(const hybrid_test::TestConfig& s, double w_rad_s) {
  CompensatedPlant loop(s);
  servo::SineTest test;
  test.frequency_hz = w_rad_s / (2.0 * M_PI);
  test.control_rate_hz = s.control_rate_hz;
  test.settling_time_s = 6.0 / test.frequency_hz;
  test.fitted_cycles = 4;
  const std::complex<double> h = servo::simulated_frequency_response(loop, test);
  return {std::abs(h), -std::arg(h) / w_rad_s};
}

std::vector<ModePrediction> modes_under_delay(const hybrid_test::TestAssembly& test, const hybrid_test::TestConfig& s) {
  const auto& numerical = test.numerical();
  const auto k = test.partition().with_specimen_stiffness(numerical.initial_stiffness());
  // Every mode of a small model, the lowest of a large one (no dense copy of its matrices).
  const Eigen::Index n = numerical.mass().rows();
  const substructure::ModalSolution modal = substructure::lowest_modes(
      numerical.mass(), k, n > substructure::kMaxDenseEigenDofs ? kLowestModesOfLargeModels : n);
  Eigen::VectorXd c_phi(n);
  std::vector<ModePrediction> modes;
  for (Eigen::Index i = 0; i < modal.omega_rad_s.size(); ++i) {
    const Eigen::VectorXd phi = modal.modes.col(i);
    const double w = modal.omega_rad_s[i];
    double k_e = 0.0;
    for (const auto& e : s.experimental)
      k_e += phi[e.dof.dof] * phi[e.dof.dof] * e.dof.force_scale * e.dof.displacement_scale *
             e.dof.specimen_stiffness_estimate_n_per_m;  // in model units, as with_specimen_stiffness adds it
    // The specimen's share acts through the loop's gain and delay at the mode's frequency.
    const LoopResponse loop = compensated_plant_response(s, w);
    numerical.damping().multiply(phi, c_phi);
    const compensation::DelayedOscillator mode{1.0, phi.dot(c_phi), w * w - k_e, k_e * loop.gain};
    ModePrediction m;
    m.loop_gain = loop.gain;
    m.loop_delay_ms = 1e3 * loop.delay_s;
    m.frequency_hz = w / (2.0 * M_PI);
    m.damping_ratio = mode.damping_n_s_per_m / (2.0 * w);
    m.experimental_share = k_e / (w * w);
    m.predicted_damping_ratio = compensation::damping_ratio_of(compensation::dominant_root(mode, loop.delay_s));
    m.critical_delay_ms = 1e3 * compensation::critical_delay_s(mode);
    modes.push_back(m);
  }
  return modes;
}

// Gives each channel the limits of its site's node; throws when the files do not fit the test.
void attach_nodes(DryRunReport& report, const hybrid_test::TestConfig& s, const std::vector<NodeLimits>& nodes) {
  for (const NodeLimits& node : nodes) {
    if (node.test_id != s.transport.test_id) {
      throw std::invalid_argument(node.name + ": node.test_id is " + std::to_string(node.test_id) +
                                  ", the scenario's transport.test_id " + std::to_string(s.transport.test_id));
    }
    std::vector<ChannelPrediction*> site;
    for (auto& c : report.channels) {
      if (c.site_id == node.site_id) site.push_back(&c);
    }
    if (site.empty()) {
      throw std::invalid_argument(node.name + ": node.site_id " + std::to_string(node.site_id) +
                                  " is not a site of the scenario's experimental channels");
    }
    if (site.front()->node)
      throw std::invalid_argument(node.name + ": a second node file for site " + std::to_string(node.site_id));
    // The site's held forces are its node's channels after its structure's.
    const auto held = static_cast<std::size_t>(std::count_if(s.held_forces.begin(), s.held_forces.end(),
                                                             [&](const auto& h) { return h.site_id == node.site_id; }));
    if (site.size() + held != node.channels.size()) {
      throw std::invalid_argument(node.name + ": " + std::to_string(node.channels.size()) +
                                  " channel(s), the scenario gives site " + std::to_string(node.site_id) + " " +
                                  std::to_string(site.size() + held) +
                                  (held > 0 ? " (" + std::to_string(held) + " of them holding a force)" : ""));
    }
    // The control mode the test sends each node channel: force on the site's held forces'.
    std::vector<std::string> held_on(node.channels.size());
    std::size_t j = site.size();
    for (const hybrid_test::HeldForce& h : s.held_forces) {
      if (h.site_id == node.site_id) held_on[j++] = hybrid_test::held_force_label(h);
    }
    for (std::size_t c = 0; c < node.control.size() && c < held_on.size(); ++c) {
      const bool force = node.control[c] == servo::ControlMode::kForce;
      if (force == !held_on[c].empty()) continue;
      throw std::invalid_argument(node.name + ": channel " + std::to_string(c) + " is in " +
                                  (force ? "force" : "displacement") +
                                  " control (actuator.control), the scenario sends it " +
                                  (held_on[c].empty() ? std::string("displacements") : "the force of " + held_on[c]) +
                                  (held_on[c].empty() ? "" : ": declare it force"));
    }
    for (std::size_t i = 0; i < site.size(); ++i)
      site[i]->node = NodeCheck{node.name, node.channels[i], node.control_period_s};
  }
}

// What the node would do with the commands the dry run sent: its limits are on the command
// (stroke, increment, velocity as increment per its own period) and the measured force.
void check_against_node(ChannelPrediction& p) {
  NodeCheck& n = *p.node;
  n.peak_command_velocity_m_per_s = p.peak_increment_m / n.control_period_s;
  n.within_limits = p.peak_command_m <= n.limits.max_stroke_m && p.peak_increment_m <= n.limits.max_increment_m &&
                    n.peak_command_velocity_m_per_s <= n.limits.max_velocity_m_per_s &&
                    p.peak_force_n <= n.limits.max_force_n;
}

// The margin left to every limit of the channel (the coordinator's, the rig's velocity, its
// node's, the converters' rails), a warning for each below kMarginWarning, and a command that
// peaks well above its target (a compensator's lead eats the stroke margin).
void add_margins(ChannelPrediction& p, std::vector<std::string>& warnings) {
  const double stroke = std::max(p.peak_command_m, p.peak_displacement_m);
  struct Shown {
    LimitMargin margin;
    double scale;
    const char* unit;
  };
  std::vector<Shown> all = {
      {margin_to("stroke", stroke, p.limits.max_stroke_m), 1e3, "mm"},
      {margin_to("increment", p.peak_increment_m, p.limits.max_increment_m), 1e3, "mm"},
      {margin_to("velocity", p.peak_velocity_m_per_s, p.rig_velocity_m_per_s), 1e3, "mm/s"},
      {margin_to("force", p.peak_force_n, p.limits.max_force_n), 1e-3, "kN"},
      {margin_to("tracking error", p.peak_tracking_error_m, p.limits.max_tracking_error_m), 1e3, "mm"},
  };
  if (p.node) {
    const NodeCheck& n = *p.node;
    all.push_back({margin_to("node stroke", p.peak_command_m, n.limits.max_stroke_m), 1e3, "mm"});
    all.push_back({margin_to("node increment", p.peak_increment_m, n.limits.max_increment_m), 1e3, "mm"});
    all.push_back(
        {margin_to("node velocity", n.peak_command_velocity_m_per_s, n.limits.max_velocity_m_per_s), 1e3, "mm/s"});
    all.push_back({margin_to("node force", p.peak_force_n, n.limits.max_force_n), 1e-3, "kN"});
  }
  all.push_back({margin_to("command D/A rail", p.peak_command_m, p.rails.command_m, true), 1e3, "mm"});
  all.push_back({margin_to("displacement A/D rail", p.peak_displacement_m, p.rails.displacement_m, true), 1e3, "mm"});
  all.push_back({margin_to("force A/D rail", p.peak_force_n, p.rails.force_n, true), 1e-3, "kN"});
  const bool leads = p.peak_target_m > 0.0 && p.peak_command_m > (1.0 + kMarginWarning) * p.peak_target_m;
  char lead[120] = "";
  if (leads) {
    std::snprintf(lead, sizeof lead, "; the command peaks %.0f %% above the target (the compensation's lead)",
                  100.0 * (p.peak_command_m / p.peak_target_m - 1.0));
  }
  for (const Shown& s : all) {
    if (!std::isfinite(s.margin.bound)) continue;
    p.margins.push_back(s.margin);
    if (s.margin.rail && s.margin.reached()) p.rail_contact = true;
    if (s.margin.low()) {
      warnings.push_back("channel " + std::to_string(p.channel) + ": " + describe(s.margin, s.scale, s.unit) +
                         (s.margin.limit.find("stroke") != std::string::npos ? lead : ""));
    }
  }
}

}  // namespace

DryRunReport dry_run(const hybrid_test::TestConfig& original, const std::vector<NodeLimits>& nodes) {
  if (!original.opensees_sites.empty()) {
    // Each OpenSees adapter serves one run: a dry run would use up the processes the test needs.
    throw std::invalid_argument(
        "a dry run cannot include OpenSees sites (opensees_sites): each adapter serves one run, and the dry run "
        "would use up the OpenSees process the test needs; check the model with `rpsd validate` instead");
  }
  hybrid_test::TestConfig s = original;
  s.transport.kind = hybrid_test::TransportConfig::Kind::kInProcess;
  s.clock.mode = hybrid_test::ClockConfig::Mode::kAsFastAsPossible;
  hybrid_test::TestAssembly test(s, {});

  const int channels = static_cast<int>(s.experimental.size());
  const double period_s = 1.0 / s.control_rate_hz;
  DryRunReport report;
  report.steps_planned = test.steps_planned();
  report.channels.resize(static_cast<std::size_t>(channels));
  std::vector<std::vector<double>> targets(channels), measured(channels);
  std::vector<double> previous_x(channels), previous_command(channels);
  // The actuator's velocity over 2 ms (at least one period): sensor noise, which a difference
  // over one period multiplies by the rate (the benchmark's 16 um at 4096 Hz reads as 0.4 m/s),
  // does not read as motion; a 20 Hz motion's peak is read to 0.3 %.
  const auto velocity_span = static_cast<std::size_t>(std::max(1.0, std::round(0.002 * s.control_rate_hz)));
  for (const auto& e : s.experimental) {
    auto& p = report.channels[static_cast<std::size_t>(e.dof.actuator_channel)];
    p.channel = e.dof.actuator_channel;
    p.site_id = e.site_id;
    // The limits the test runs with: the rig's envelope unless the scenario tightens it (a
    // setup's channel: its actuator's, below).
    const bool setup_dof = std::any_of(s.setups.begin(), s.setups.end(), [&](const auto& site) {
      return std::find(site.channels.begin(), site.channels.end(), p.channel) != site.channels.end();
    });
    if (!setup_dof) {
      p.limits = coordinator::within_envelope(e.limits, servo::envelope_of(s.plant), test.control_period_s());
    }
    p.rig_velocity_m_per_s = servo::envelope_of(s.plant).velocity_m_per_s;
    p.rails = converter_rails(s.plant);
  }
  Eigen::VectorXd hold(channels);
  test.partition().extract_commands(s.initial_displacement_m, hold);
  // A setup's channels: each actuator's own limits, and its rest at the strokes of the
  // initial configuration; its DOFs predicted against their own limits.
  const hybrid_test::SetupPlan plan = hybrid_test::plan_setups(s, hold, test.control_period_s(), false);
  for (std::size_t k = 0; k < plan.groups.size(); ++k) {
    const coordinator::SetupGroup& group = plan.groups[k];
    for (std::size_t i = 0; i < group.channels.size(); ++i) {
      const auto c = static_cast<std::size_t>(group.channels[i]);
      report.channels[c].limits = group.actuator_limits[i];
      DofPrediction d;
      d.channel = group.channels[i];
      d.site_id = group.site_id;
      d.motion = std::string(setups::dof_motion_name(group.geometry.dofs[i]));
      for (const auto& e : s.experimental) {
        if (e.dof.actuator_channel == d.channel) d.limits = e.limits;
      }
      report.dofs.push_back(d);
    }
  }
  for (int c = 0; c < channels; ++c) hold[c] = plan.hold_m[static_cast<std::size_t>(c)];
  attach_nodes(report, s, nodes);
  for (int c = 0; c < channels; ++c) previous_x[c] = previous_command[c] = hold[c];

  const auto watch = [&](const coordinator::StepRecord& r) {
    for (int c = 0; c < channels; ++c) {
      auto& p = report.channels[static_cast<std::size_t>(c)];
      p.peak_command_m = std::max(p.peak_command_m, std::abs(r.command_m[c]));
      p.peak_displacement_m = std::max(p.peak_displacement_m, std::abs(r.measured_m[c]));
      const auto& history = measured[static_cast<std::size_t>(c)];
      const bool spanned = history.size() >= velocity_span;  // else from the start, at rest at hold
      const double earlier_x = spanned ? history[history.size() - velocity_span] : hold[c];
      const double span_s = static_cast<double>(spanned ? velocity_span : history.size() + 1) * period_s;
      p.peak_velocity_m_per_s = std::max(p.peak_velocity_m_per_s, std::abs(r.measured_m[c] - earlier_x) / span_s);
      p.peak_increment_m = std::max(p.peak_increment_m, std::abs(r.command_m[c] - previous_command[c]));
      p.peak_force_n = std::max(p.peak_force_n, std::abs(r.measured_force_n[c]));
      p.peak_target_m = std::max(p.peak_target_m, std::abs(r.target_m[c]));
      p.peak_tracking_error_m = std::max(p.peak_tracking_error_m, std::abs(r.measured_m[c] - r.target_m[c]));
      previous_x[c] = r.measured_m[c];
      previous_command[c] = r.command_m[c];
      targets[c].push_back(r.target_m[c]);
      measured[c].push_back(r.measured_m[c]);
      const servo::Plant* plant = test.actuators().simulated_plant(c);
      if (const auto* converted = dynamic_cast<const servo::ConvertedPlant*>(plant)) plant = &converted->plant();
      if (const auto* servo = dynamic_cast<const servo::ServoHydraulicPlant*>(plant)) {
        p.peak_valve_opening = std::max(p.peak_valve_opening.value_or(0.0), std::abs(servo->spool_opening()));
      }
    }
  };
  const auto watch_dofs = [&](const coordinator::StepRecord& r) {
    watch(r);
    for (DofPrediction& d : report.dofs) {
      d.peak_target_m = std::max(d.peak_target_m, std::abs(r.dof_target_m[d.channel]));
      d.peak_displacement_m = std::max(d.peak_displacement_m, std::abs(r.dof_measured_m[d.channel]));
      d.peak_force_n = std::max(d.peak_force_n, std::abs(r.dof_force_n[d.channel]));
      d.peak_tracking_error_m =
          std::max(d.peak_tracking_error_m, std::abs(r.dof_measured_m[d.channel] - r.dof_target_m[d.channel]));
    }
  };
  const coordinator::StepOutcome outcome = report.dofs.empty() ? test.run(watch, {}) : test.run(watch_dofs, {});
  const hybrid_test::TestRun run = test.finish(outcome);
  report.outcome = run.outcome;
  report.limit_stop = run.limit_stop;
  report.steps = run.steps;
  for (std::size_t k = 0; k < run.held_forces.size(); ++k) {
    const coordinator::HeldForceChannel& c = run.held_forces[k];
    HeldForcePrediction h;
    h.name = c.name.data();
    h.site_id = c.site_id;
    h.channel = c.channel;
    h.force_n = c.force_n;
    h.max_force_rate_n_per_s = c.max_force_rate_n_per_s;
    h.force_at_rest_n = c.force_at_rest_n;
    h.limits = c.limits;
    h.ramp_s = hybrid_test::held_force_ramp_s(s.held_forces[k], c.force_at_rest_n);
    if (k < run.held_stats.size()) {
      const hybrid_test::HeldForceStats& st = run.held_stats[k];
      h.max_force_error_after_ramp_n = st.max_force_error_after_ramp_n;
      if (st.steps > 0) h.peak_measured_m = std::max(std::abs(st.min_measured_m), std::abs(st.max_measured_m));
    }
    // A stop on the held force's channel belongs in its peaks.
    if (report.limit_stop.channel == c.channel && report.limit_stop.kind == coordinator::LimitStop::Kind::kStroke)
      h.peak_measured_m = std::max(h.peak_measured_m, std::abs(report.limit_stop.value));
    h.within_limits = h.peak_measured_m <= h.limits.max_stroke_m &&
                      !(h.max_force_error_after_ramp_n > h.limits.max_force_error_n) &&
                      std::abs(h.force_n) <= h.limits.max_force_n;
    report.held_forces.push_back(h);
  }

  // The value that stopped the run was never sent or recorded: it belongs in the peaks, so
  // that its limit shows as reached (margin <= 0), not with the margin of the last step taken.
  const coordinator::LimitStop& stop = report.limit_stop;
  // A DOF's limit: its peaks, not its actuator's.
  for (DofPrediction& d : report.dofs) {
    if (stop.dof < 0 || stop.channel != d.channel) continue;
    const double v = std::abs(stop.value);
    if (stop.kind == coordinator::LimitStop::Kind::kStroke) d.peak_target_m = std::max(d.peak_target_m, v);
    if (stop.kind == coordinator::LimitStop::Kind::kForce) d.peak_force_n = std::max(d.peak_force_n, v);
    if (stop.kind == coordinator::LimitStop::Kind::kTrackingError)
      d.peak_tracking_error_m = std::max(d.peak_tracking_error_m, v);
  }
  if (stop.dof < 0 && stop.channel >= 0 && stop.channel < channels) {
    auto& p = report.channels[static_cast<std::size_t>(stop.channel)];
    const double v = std::abs(stop.value);
    switch (stop.kind) {
      case coordinator::LimitStop::Kind::kStroke:
        p.peak_command_m = std::max(p.peak_command_m, v);
        break;
      case coordinator::LimitStop::Kind::kIncrement:
        p.peak_increment_m = std::max(p.peak_increment_m, v);
        break;
      case coordinator::LimitStop::Kind::kForce:
        p.peak_force_n = std::max(p.peak_force_n, v);
        break;
      case coordinator::LimitStop::Kind::kTrackingError:
        p.peak_tracking_error_m = std::max(p.peak_tracking_error_m, v);
        break;
      default:
        break;
    }
  }
  double delay_sum_ms = 0.0;
  int delays = 0;
  for (int c = 0; c < channels; ++c) {
    auto& p = report.channels[static_cast<std::size_t>(c)];
    if (const auto delay = signed_delay(targets[c], measured[c], s.control_rate_hz)) {
      p.tracking_delay_ms = 1e3 * delay->delay_samples / s.control_rate_hz;
      p.tracking_delay_at_window_edge = delay->at_boundary;
    }
    if (p.tracking_delay_ms) {
      delay_sum_ms += *p.tracking_delay_ms;
      ++delays;
    }
    // The increment limit holds the command; the others the measurement.
    p.within_limits = p.peak_command_m <= p.limits.max_stroke_m && p.peak_displacement_m <= p.limits.max_stroke_m &&
                      p.peak_increment_m <= p.limits.max_increment_m && p.peak_force_n <= p.limits.max_force_n;
    if (p.node) {
      check_against_node(p);
      p.within_limits = p.within_limits && p.node->within_limits;
    }
    add_margins(p, report.warnings);
  }
  for (DofPrediction& d : report.dofs) {
    d.within_limits = std::max(d.peak_target_m, d.peak_displacement_m) <= d.limits.max_stroke_m &&
                      d.peak_force_n <= d.limits.max_force_n &&
                      d.peak_tracking_error_m <= d.limits.max_tracking_error_m;
  }
  report.residual_delay_ms = delays > 0 ? delay_sum_ms / delays : 0.0;
  report.modes = modes_under_delay(test, s);

  if (const auto* servo = std::get_if<servo::ServoSystemParameters>(&s.plant)) {
    const servo::ServoAnalysis a = servo::analyze(*servo);
    report.p_gain = a.p_gain;
    report.max_stable_p_gain = a.max_stable_p_gain_full_model;
  }
  report.actuator_cutoff_hz = actuator_cutoff_hz(s.plant);
  if (report.actuator_cutoff_hz) {
    std::vector<double> frequencies;
    for (const auto& m : report.modes) frequencies.push_back(m.frequency_hz);
    for (auto& w : modes_beyond_bandwidth(frequencies, *report.actuator_cutoff_hz, mass_key(s))) {
      report.warnings.push_back(std::move(w));
    }
  }
  const bool completed =
      report.outcome == coordinator::StepOutcome::kOk || report.outcome == coordinator::StepOutcome::kRecordEnded;
  report.within_limits =
      completed &&
      std::all_of(report.channels.begin(), report.channels.end(),
                  [](const auto& p) { return p.within_limits && !p.rail_contact; }) &&
      std::all_of(report.dofs.begin(), report.dofs.end(), [](const auto& d) { return d.within_limits; }) &&
      std::all_of(report.held_forces.begin(), report.held_forces.end(),
                  [](const auto& h) { return h.within_limits; }) &&
      std::all_of(report.modes.begin(), report.modes.end(),
                  [](const auto& m) { return m.predicted_damping_ratio > 0.0; }) &&
      (!report.p_gain || *report.p_gain < *report.max_stable_p_gain);
  return report;
}

hybrid_test::TestConfig simulated_in_process(const hybrid_test::TestConfig& scenario) {
  hybrid_test::TestConfig s = scenario;
  s.transport.kind = hybrid_test::TransportConfig::Kind::kInProcess;
  s.clock.mode = hybrid_test::ClockConfig::Mode::kAsFastAsPossible;
  s.telemetry.enabled = false;
  return s;
}

double predicted_lowest_mode_damping(const hybrid_test::TestConfig& original) {
  if (!original.opensees_sites.empty()) return std::numeric_limits<double>::quiet_NaN();
  try {
    const hybrid_test::TestConfig s = simulated_in_process(original);
    const hybrid_test::TestAssembly test(s, {});
    const std::vector<ModePrediction> modes = modes_under_delay(test, s);
    return modes.empty() ? std::numeric_limits<double>::quiet_NaN() : modes.front().predicted_damping_ratio;
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();  // the run itself says what is wrong
  }
}

}  // namespace rpsd::studies
