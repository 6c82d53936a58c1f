#include "rpsd/hybrid_test/hybrid_test_assembly.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "rpsd/coordinator/recorder.h"
#include "rpsd/hybrid_test/actuator_links.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/hybrid_test/setup_plan.h"
#include "rpsd/realtime/latency_histogram.h"
#include "rpsd/realtime/pacer.h"
#include "rpsd/substructure/ground_motion_load.h"

namespace rpsd::hybrid_test {

struct TestAssembly::Parts {
  const TestConfig* config = nullptr;
  bool real_time = false;
  std::unique_ptr<substructure::NumericalModel> numerical;
  substructure::Partition partition;
  std::unique_ptr<integrators::Integrator> integrator;
  std::vector<std::unique_ptr<compensation::CommandCompensator>> compensators;
  std::unique_ptr<ActuatorLinks> actuators;
  std::unique_ptr<transport::Link> wrapped_link;  // AssemblyOptions::wrap_link around the actuators
  substructure::GroundMotionLoad ground_load;
  std::unique_ptr<coordinator::RpsdLoop> loop;
  std::unique_ptr<coordinator::Recorder> recorder;
  coordinator::LiveCounters live;  // for watchers on other threads (AssemblyOptions::record_observers)
  std::vector<realtime::LatencyHistogram> round_trips;  // per site, its first channel
  std::vector<std::size_t> round_trip_channels;         // per site, that channel
  // Per site, its round trips of 0 s (every step in process: the node answers in the same
  // call), added to its histogram at finish(): the same summary, no histogram update a step.
  std::vector<std::int64_t> zero_round_trips;
  // Whether a site's node can refuse the run once it is under way: only one over DDS hears so
  // later (its link, DdsSite::refused); the others are asked before the first step only.
  bool refusal_may_come = false;
  std::int64_t steps_planned = 0;
  std::int64_t steps = 0;
  TimingReport timing;
  std::vector<SetupCalibration> calibrations;              // per experimental setup
  std::vector<coordinator::HeldForceChannel> held_forces;  // as the loop was given them
  HeldForceTracker held_stats;                             // of held_forces, from every step's record
  realtime::CpuWakeLatencyHold cpus_awake;                 // from the start to finish(): real time, or over DDS
  const std::atomic<bool>* stop_request = nullptr;
  operator_commands::OperatorControl* operator_control = nullptr;
  Eigen::VectorXd start_targets;  // each channel's target at rest before the first step
  std::vector<HeldInterval> held;
  std::string operator_sender;
  ReturnToStart return_to_start;
  bool operator_ended = false;  // an operator's stop or abort was acted on
  // The host program's parts (kind external), to ask after each step whether a call failed.
  std::vector<const compensation::ExternalCompensator*> external_compensators;
  const substructure::ExternalStructureModel* external_structure = nullptr;

  // Whether a host call failed (one load per part). Real-time safe.
  bool host_failed() const noexcept {
    if (external_structure && external_structure->failed()) return true;
    return !external_compensators.empty() &&  // most tests have none: no loop set up a step
           std::any_of(external_compensators.begin(), external_compensators.end(),
                       [](const compensation::ExternalCompensator* c) { return c->failed(); });
  }

  // Which host part failed, in which call, in the host's words. Not real-time safe.
  std::string host_error() const {
    if (external_structure && external_structure->failed()) {
      return "structure external `" + external_structure->host_name() + "` " + external_structure->failure();
    }
    for (const compensation::ExternalCompensator* c : external_compensators) {
      if (c->failed()) {
        return "compensation external `" + c->host_name() + "` (channel " + std::to_string(c->channel()) + ") " +
               c->failure();
      }
    }
    return {};
  }

  // Counts a step the loop took. What it reads of the step is asked of the loop's parts
  // (the round trips) or of its record only when needed (the held forces' statistics): the
  // record is unpacked from its row when first asked for. Real-time safe.
  void took_step() {
    ++steps;
    live.steps_done.store(steps, std::memory_order_relaxed);
    live.late_feedback.store(loop->late_feedback_total(), std::memory_order_relaxed);
    if (!held_forces.empty()) held_stats.add(loop->last_record());
    const coordinator::ExperimentalExchange& exchange = loop->exchange();
    for (std::size_t i = 0; i < round_trip_channels.size(); ++i) {
      // A round trip of 0 ns is one of 0 s (its record's value) and no other is: asked as an integer.
      if (exchange.feedback().round_trip_ns[round_trip_channels[i]] == 0) {
        ++zero_round_trips[i];
      } else {
        const double round_trip_s = exchange.round_trip_s(static_cast<int>(round_trip_channels[i]));
        round_trips[i].add(static_cast<std::int64_t>(std::llround(round_trip_s * 1e9)));
      }
    }
  }

  // Why the run stops although its step succeeded: the records cannot be written, the user
  // asked it to stop, or an operator did. An operator's hold (lock-step only) waits here, after
  // the step, until it is lifted. Real-time safe but for the hold (which real time refuses).
  coordinator::StepOutcome stop_after_step() {
    if (host_failed()) return coordinator::StepOutcome::kHostCallFailed;
    if (recorder->write_failed()) return coordinator::StepOutcome::kResultsNotWritten;
    if (stop_request && stop_request->load(std::memory_order_relaxed)) return coordinator::StepOutcome::kInterrupted;
    if (!operator_control) return coordinator::StepOutcome::kOk;
    if (!real_time && operator_control->hold_requested()) hold_while_asked();
    return operator_outcome();
  }

  // The operator's stop or abort, acted on: the abort tells every node the run is over at once
  // (each holds where its command is); the stop returns to the start positions first when the
  // scenario asks for it, then ends the run the same way. kOk when neither was asked.
  coordinator::StepOutcome operator_outcome() {
    using operator_commands::OperatorRequest;
    const OperatorRequest request = operator_control->request();
    if (request == OperatorRequest::kNone) return coordinator::StepOutcome::kOk;
    if (operator_ended)
      return request == OperatorRequest::kAbort ? coordinator::StepOutcome::kOperatorAbort
                                                : coordinator::StepOutcome::kOperatorStop;
    operator_ended = true;
    if (request == OperatorRequest::kStop && config->operator_commands.return_to_start) return_to_start_positions();
    // Asked after the return: an abort during it replaces the stop.
    const bool aborted = operator_control->request() == OperatorRequest::kAbort;
    actuators->end_run();
    operator_sender = operator_control->requested_by();
    return aborted ? coordinator::StepOutcome::kOperatorAbort : coordinator::StepOutcome::kOperatorStop;
  }

  // Lock-step: takes no step while an operator holds the test; the actuators hold their last
  // command and every node over DDS hears the run is alive. A stop, an abort or SIGINT while
  // held ends the hold (and the run). Not real-time safe (allocates the interval's record).
  void hold_while_asked() {
    HeldInterval interval;
    interval.after_step = steps;
    interval.start_unix_ns = unix_now_ns();
    interval.held_by = operator_control->held_by();
    auto next_keep_alive = std::chrono::steady_clock::now();
    operator_control->set_holding(true);
    while (operator_control->hold_requested() &&
           operator_control->request() == operator_commands::OperatorRequest::kNone &&
           !(stop_request && stop_request->load(std::memory_order_relaxed))) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_keep_alive) {
        actuators->keep_run_alive();
        next_keep_alive = now + std::chrono::milliseconds(500);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    operator_control->set_holding(false);
    if (!operator_control->hold_requested()) {
      interval.end_unix_ns = unix_now_ns();
      interval.resumed_by = operator_control->resumed_by();
    }
    held.push_back(std::move(interval));
  }

  static std::int64_t unix_now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  }

  // Ramps every channel's target from where the stop left its command to its start position at the
  // stated velocity and holds it there for half a second, one exchange per control period
  // (paced on the wall clock when a rig may be on the other side: real time or over DDS),
  // within the coordinator's limits; stops at the first exchange that is not kOk. The rows
  // are sized before the first exchange.
  void return_to_start_positions() {
    ReturnToStart& r = return_to_start;
    r.asked = true;
    const double period_s = 1.0 / config->control_rate_hz / integrator->iterations_per_step();
    r.velocity_m_per_s = config->operator_commands.return_velocity_m_per_s;
    const double step_m = r.velocity_m_per_s * period_s;
    // The ramp starts where each channel's command is and goes uncompensated: no jump at its
    // first exchange, and no lead on a ramp too slow to need any.
    const auto channels = static_cast<int>(loop->exchange().targets().size());
    Eigen::VectorXd from(channels);
    for (int c = 0; c < channels; ++c) from[c] = loop->exchange().command_in_target_space(c);
    loop->set_compensated(false);
    r.channels = channels;
    double farthest_m = 0.0;
    for (int c = 0; c < channels; ++c) farthest_m = std::max(farthest_m, std::abs(start_targets[c] - from[c]));
    // Then the start target is held for kSettleS, so that the actuators settle on it.
    constexpr double kSettleS = 0.5;
    const auto ramp = static_cast<std::int64_t>(std::ceil(farthest_m / step_m));
    const auto exchanges = ramp + static_cast<std::int64_t>(std::ceil(kSettleS / period_s));
    r.rows.assign(static_cast<std::size_t>(exchanges) * static_cast<std::size_t>(1 + 4 * channels), 0.0);
    Eigen::VectorXd target = from;
    const bool paced = real_time || actuators->over_dds();
    const auto period_ns = static_cast<std::int64_t>(std::llround(period_s * 1e9));
    realtime::Pacer pacer(period_ns);
    if (paced) pacer.start();
    const double t0_s = loop->last_record().time_s;
    for (std::int64_t k = 1; k <= exchanges; ++k) {
      for (int c = 0; c < channels; ++c) {
        const double to_go = start_targets[c] - from[c];
        const double moved = std::min(std::abs(to_go), step_m * static_cast<double>(k));
        target[c] = from[c] + std::copysign(moved, to_go);
      }
      if (paced) {
        pacer.wait_next();
        actuators->set_receive_deadline_ns(real_time ? pacer.current_deadline_ns() + period_ns * 8 / 10 : 0);
      }
      const double time_s = t0_s + period_s * static_cast<double>(k);
      const coordinator::StepOutcome o = loop->exchange_only(target, time_s);
      if (o != coordinator::StepOutcome::kOk) {
        r.outcome = o;
        r.limit_stop = loop->limit_stop();
        break;
      }
      const transport::CommandSample& cmd = loop->exchange().command();
      const transport::FeedbackSample& fb = loop->exchange().feedback();
      double* row = r.rows.data() + static_cast<std::size_t>(k - 1) * static_cast<std::size_t>(1 + 4 * channels);
      row[0] = time_s;
      for (int c = 0; c < channels; ++c) {
        row[1 + 4 * c] = target[c];
        row[2 + 4 * c] = cmd.displacement_m[static_cast<std::size_t>(c)];
        row[3 + 4 * c] = fb.displacement_m[static_cast<std::size_t>(c)];
        row[4 + 4 * c] = fb.force_n[static_cast<std::size_t>(c)];
      }
      r.exchanges = k;
      if (operator_control->request() == operator_commands::OperatorRequest::kAbort) break;
    }
    r.rows.resize(static_cast<std::size_t>(r.exchanges) * static_cast<std::size_t>(1 + 4 * channels));
  }
};

TestAssembly::TestAssembly(const TestConfig& s, const AssemblyOptions& options) : parts_(std::make_unique<Parts>()) {
  const bool perfect_actuator = options.perfect_actuator;
  // A host program's code (a Python callable) may take any time and allocate: lock-step only.
  if (s.clock.mode == ClockConfig::Mode::kRealTime && uses_external_parts(s)) {
    throw std::invalid_argument(
        "a compensator or structure of kind external (given by a host program) runs lock-step only "
        "(clock.mode as_fast_as_possible): nothing external runs on a real-time path");
  }
  Parts& p = *parts_;
  p.config = &s;
  p.numerical =
      make_numerical_model(s, perfect_actuator ? SpecimenShare::kKeptInNumericalPart : SpecimenShare::kLeftToSpecimens);
  p.external_structure = dynamic_cast<const substructure::ExternalStructureModel*>(p.numerical.get());
  const Eigen::Index dofs = p.numerical->dofs();
  const int channels = static_cast<int>(s.experimental.size());

  p.partition.configure(partition_config(s, dofs));

  p.integrator = integrators::make_integrator(s.integrator);
  const double dt_s = 1.0 / s.control_rate_hz;
  p.integrator->configure({p.numerical->mass(), p.numerical->damping(),
                           p.partition.with_specimen_stiffness(p.numerical->initial_stiffness())},
                          dt_s);
  const double control_period_s = dt_s / p.integrator->iterations_per_step();

  coordinator::LoopParts parts;
  parts.compensators.resize(static_cast<std::size_t>(channels));
  parts.force_paths.resize(static_cast<std::size_t>(channels));
  for (const auto& channel : s.experimental) {
    // The loop wants channel order; the partition numbered the channels 0..n-1.
    const auto ch = static_cast<std::size_t>(channel.dof.actuator_channel);
    // An OpenSees site is numerical: no lag to compensate, no rig to limit.
    const bool numerical_site = s.opensees_site(channel.site_id) != nullptr;
    p.compensators.push_back(compensation::make_compensator(
        perfect_actuator || numerical_site ? compensation::CompensatorConfig{compensation::PassThroughParameters{}}
                                           : s.compensation,
        control_period_s, static_cast<int>(ch)));
    parts.compensators[ch] = p.compensators.back().get();
    if (const auto* external = dynamic_cast<const compensation::ExternalCompensator*>(p.compensators.back().get()))
      p.external_compensators.push_back(external);
    // The rig's envelope is every limit's default; the reference is numerical: no rig, no limits.
    // A DOF a setup drives keeps its limits as given: the rig's envelope is its actuators'.
    const bool setup_dof = std::any_of(s.setups.begin(), s.setups.end(), [&](const ExperimentalSetupSite& site) {
      return std::find(site.channels.begin(), site.channels.end(), static_cast<int>(ch)) != site.channels.end();
    });
    if (!perfect_actuator) {
      parts.limits.resize(static_cast<std::size_t>(channels));
      parts.limits[ch] =
          numerical_site || setup_dof
              ? (setup_dof ? coordinator::per_control_period(channel.limits, control_period_s)
                           : coordinator::CoordinatorLimits{})
              : coordinator::within_envelope(channel.limits, servo::envelope_of(s.plant), control_period_s);
    }
    parts.force_paths[ch] = {channel.restoring_force, channel.dof.specimen_stiffness_estimate_n_per_m};
  }

  // Start at rest at the initial displacement, the specimens holding it. The run's identity
  // is drawn now: no other run, of this test id or any, carries it.
  // A setup's actuators rest at the strokes of its DOFs' initial targets.
  Eigen::VectorXd hold(channels);
  p.partition.extract_commands(s.initial_displacement_m, hold);
  SetupPlan setups = plan_setups(s, hold, control_period_s, perfect_actuator);
  const std::uint64_t run_id = transport::draw_run_id();
  const auto per_channel = [&](const std::vector<double>& v) { return std::span<const double>(v.data(), v.size()); };
  p.actuators = std::make_unique<ActuatorLinks>(
      s, control_period_s, perfect_actuator, per_channel(setups.hold_m), run_id,
      s.setups.empty() ? std::span<const double>{} : per_channel(setups.stiffness_estimate_n_per_m));
  // Calibration: each setup actuator's reading at rest against the stroke the geometry predicts.
  if (!s.setups.empty()) {
    std::vector<std::optional<double>> readings(static_cast<std::size_t>(channels));
    for (int c = 0; c < channels; ++c) readings[static_cast<std::size_t>(c)] = p.actuators->initial_reading_m(c);
    p.calibrations = calibrate_setups(s, setups, readings);
    for (SetupCalibration& cal : p.calibrations) {
      for (int c : cal.channels) {
        cal.force_at_rest_n.push_back(p.actuators->initial_force_n(c));
        cal.force_at_rest_measured = cal.force_at_rest_measured && p.actuators->initial_force_measured(c);
      }
    }
  }

  parts.integrator = p.integrator.get();
  parts.numerical = p.numerical.get();
  parts.partition = &p.partition;
  p.stop_request = options.stop_request;
  p.operator_control = perfect_actuator ? nullptr : options.operator_control;
  p.start_targets = hold;
  if (options.wrap_link) p.wrapped_link = options.wrap_link(p.actuators->link());
  parts.link = p.wrapped_link ? p.wrapped_link.get() : &p.actuators->link();
  parts.recorded_dofs = s.record_dofs;
  parts.test_id = s.transport.test_id;
  parts.run_id = run_id;
  p.real_time = s.clock.mode == ClockConfig::Mode::kRealTime && !perfect_actuator;
  parts.max_feedback_age_periods = p.real_time ? s.clock.max_feedback_age_periods : 0;
  parts.stop_on_node_limits = !perfect_actuator;
  // The reference is the whole structure integrated on its own: no loop to time.
  parts.timing = perfect_actuator ? coordinator::LoopTiming::kEndOfStep : s.clock.loop_timing;
  parts.max_valve_saturation_exchanges =
      perfect_actuator
          ? 0
          : std::max(1, static_cast<int>(std::lround(s.run_away.max_valve_saturation_s / control_period_s)));
  if (s.ground_motion) {
    p.ground_load.configure(whole_structure_mass(s), s.influence);
    parts.ground_acceleration_m_per_s2 = s.ground_motion->acceleration_m_per_s2;
    parts.ground_load = &p.ground_load;
  }
  std::vector<double> force0(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    const coordinator::RestoringForcePath& path = parts.force_paths[static_cast<std::size_t>(c)];
    force0[static_cast<std::size_t>(c)] = path.source == coordinator::RestoringForceSource::kMeasuredForce
                                              ? p.actuators->initial_force_n(c)
                                              : path.stiffness_n_per_m * hold[c];
  }
  // A setup's DOFs carry Jᵀ f of its actuators' forces at rest.
  for (const coordinator::SetupGroup& group : setups.groups) {
    const setups::PlanarSetup setup(group.geometry);
    const int n = setup.dofs();
    setups::SetupVector u0(n), f(n), dof_f(n);
    for (int i = 0; i < n; ++i) {
      const int c = group.channels[static_cast<std::size_t>(i)];
      u0[i] = hold[c];
      f[i] = p.actuators->initial_force_n(c);
    }
    setup.dof_forces(u0, f, dof_f);
    for (int i = 0; i < n; ++i) {
      const auto c = static_cast<std::size_t>(group.channels[static_cast<std::size_t>(i)]);
      const coordinator::RestoringForcePath& path = parts.force_paths[c];
      if (path.source == coordinator::RestoringForceSource::kMeasuredForce) force0[c] = dof_f[i];
    }
  }
  parts.setups = std::move(setups.groups);
  // The held forces ramp from what their load cells read at rest; the perfect-actuator
  // reference is numerical and holds none.
  if (!perfect_actuator) {
    for (std::size_t k = 0; k < s.held_forces.size(); ++k) {
      p.held_forces.push_back(held_force_channel(s, k, p.actuators->initial_force_n(held_force_link_channel(s, k))));
    }
  }
  parts.held_forces = p.held_forces;
  p.held_stats = HeldForceTracker(p.held_forces);
  p.loop = std::make_unique<coordinator::RpsdLoop>(std::move(parts));
  p.loop->start(s.initial_displacement_m, force0);

  // A paced loop must wake on time, and lock-step over DDS waits one round trip per step whose
  // wake-ups land on other CPUs; both are slow from an idle state (docs/dds-transport.md).
  // The CPUs are kept awake until finish(), whichever way the steps are taken. As fast as
  // possible in process there is no such wake-up, and the CPUs are left alone.
  if (p.real_time || p.actuators->over_dds()) {
    realtime::RealTimeSetupReport awake;
    p.cpus_awake = realtime::hold_cpus_awake(s.clock.realtime, awake);
    p.timing.cpus_kept_awake = awake.cpus_kept_awake;
    p.timing.refused = awake.refused;
  }

  p.steps_planned = static_cast<std::int64_t>(std::llround(s.duration_s * s.control_rate_hz));
  if (p.loop->steps_available() >= 0) p.steps_planned = std::min(p.steps_planned, p.loop->steps_available());
  p.round_trips.resize(p.actuators->sites().size());
  p.zero_round_trips.assign(p.actuators->sites().size(), 0);
  for (const auto& site : p.actuators->sites())
    p.round_trip_channels.push_back(static_cast<std::size_t>(site.channels.front()));
  p.refusal_may_come = p.actuators->over_dds();
  coordinator::RecorderOptions recording = recorded_columns(s, perfect_actuator);
  recording.keep_records = options.keep_records;
  recording.observers = options.record_observers;
  recording.csv_every_steps = s.histories.every_steps;  // output.histories: decimated
  // A paced run's rows reach the file within about a period of their step: a kill -9 loses
  // no more than the step in flight (coordinator::RecorderOptions::idle_poll).
  if (p.real_time || p.actuators->over_dds())
    recording.idle_poll = coordinator::paced_idle_poll(1.0 / s.control_rate_hz);
  // The structure's channels; the held forces' columns follow (RecorderOptions::held_channels).
  p.recorder =
      std::make_unique<coordinator::Recorder>(options.csv, channels, static_cast<int>(s.record_dofs.size()), recording);
}

coordinator::RecorderOptions recorded_columns(const TestConfig& s, bool perfect_actuator) {
  coordinator::RecorderOptions recording;
  for (const ExperimentalSetupSite& site : s.setups) {
    const setups::PlanarGeometry g = setups::planar_geometry(site.setup);
    for (std::size_t i = 0; i < site.channels.size(); ++i) {
      recording.dof_view.push_back({site.channels[i], g.dofs[i] == setups::DofMotion::kRotation});
    }
  }
  // As the held forces' channels (held_force_channel); the reference holds none.
  for (std::size_t k = 0; k < (perfect_actuator ? 0 : s.held_forces.size()); ++k)
    recording.held_channels.push_back(held_force_link_channel(s, k));
  return recording;
}

TestAssembly::~TestAssembly() = default;

std::uint64_t TestAssembly::run_id() const { return parts_->loop->run_id(); }

const coordinator::LiveCounters& TestAssembly::live_counters() const { return parts_->live; }

std::int64_t TestAssembly::steps_planned() const { return parts_->steps_planned; }

bool TestAssembly::real_time() const { return parts_->real_time; }

double TestAssembly::control_period_s() const {
  return 1.0 / parts_->config->control_rate_hz / parts_->integrator->iterations_per_step();
}

std::int64_t TestAssembly::progress_every_steps() const {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(0.5 * parts_->config->control_rate_hz));
}

coordinator::StepOutcome TestAssembly::step() {
  Parts& p = *parts_;
  if ((p.steps == 0 || p.refusal_may_come) && p.actuators->refused()) return coordinator::StepOutcome::kRefused;
  coordinator::StepOutcome outcome = p.loop->step(*p.recorder);
  if (outcome == coordinator::StepOutcome::kOk) {
    p.took_step();
    outcome = p.stop_after_step();
  }
  return outcome;
}

const coordinator::StepRecord& TestAssembly::last_record() const { return parts_->loop->last_record(); }

const coordinator::LimitStop& TestAssembly::limit_stop() const { return parts_->loop->limit_stop(); }

coordinator::StepOutcome TestAssembly::run(const std::function<void(const coordinator::StepRecord&)>& after_step,
                                           const std::function<void(std::int64_t, std::int64_t)>& progress) {
  Parts& p = *parts_;
  coordinator::RpsdLoop& loop = *p.loop;
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;
  if (p.actuators->refused()) return coordinator::StepOutcome::kRefused;
  if (!p.real_time) {
    const std::int64_t report_every = progress_every_steps();
    for (std::int64_t n = 0; n < p.steps_planned; ++n) {
      outcome = loop.step(*p.recorder);
      if (outcome != coordinator::StepOutcome::kOk) break;
      p.took_step();
      if (after_step) after_step(loop.last_record());
      outcome = p.stop_after_step();
      if (outcome != coordinator::StepOutcome::kOk) break;
      if (progress && (n + 1) % report_every == 0) progress(n + 1, p.steps_planned);
    }
    return outcome;
  }
  // The paced loop: absolute deadlines at the integration step; each cycle may wait for its
  // feedback until a fraction of the period is left for the integrator and the recorder.
  TimingReport& timing = p.timing;
  timing.real_time = true;
  loop.set_wait_for_recorder(false);  // the paced loop never waits on the writer: it drops and counts
  const realtime::RealTimeSetupReport granted = realtime::apply_realtime(p.config->clock.realtime);
  timing.memory_locked = granted.memory_locked;
  timing.fifo_granted = granted.fifo_granted;
  timing.pinned_cpu = granted.pinned_cpu;
  timing.refused += granted.refused;
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / p.config->control_rate_hz));
  realtime::Pacer pacer(period_ns);
  realtime::LatencyHistogram jitter;
  // The first exchange may wait the full feedback timeout (the link's first sample, page
  // faults after mlockall); the clock starts once it is done.
  if (p.steps_planned > 0) {
    p.actuators->set_receive_deadline_ns(0);
    outcome = loop.step(*p.recorder);
    if (outcome != coordinator::StepOutcome::kOk) return outcome;
    p.took_step();
    if (after_step) after_step(loop.last_record());
    outcome = p.stop_after_step();
    if (outcome != coordinator::StepOutcome::kOk) return outcome;
  }
  pacer.start();
  for (std::int64_t n = 1; n < p.steps_planned; ++n) {
    const std::int64_t late_ns = pacer.wait_next();
    jitter.add(late_ns);
    loop.set_cycle_lateness_ns(late_ns);
    p.actuators->set_receive_deadline_ns(pacer.current_deadline_ns() + period_ns * 8 / 10);
    outcome = loop.step(*p.recorder);
    p.live.overruns.store(pacer.overruns(), std::memory_order_relaxed);
    if (outcome != coordinator::StepOutcome::kOk) break;
    p.took_step();
    if (after_step) after_step(loop.last_record());
    outcome = p.stop_after_step();
    if (outcome != coordinator::StepOutcome::kOk) break;
  }
  timing.cycles = pacer.cycles();
  timing.overruns = pacer.overruns();
  timing.skipped_deadlines = pacer.skipped_deadlines();
  timing.jitter = jitter.summary();
  timing.late_feedback = loop.late_feedback_total();
  return outcome;
}

const substructure::NumericalModel& TestAssembly::numerical() const { return *parts_->numerical; }
const substructure::Partition& TestAssembly::partition() const { return parts_->partition; }
const ActuatorLinks& TestAssembly::actuators() const { return *parts_->actuators; }

TestRun TestAssembly::finish(coordinator::StepOutcome outcome) {
  Parts& p = *parts_;
  p.cpus_awake = {};
  TestRun run;
  // Asked before the run ends: the node's heartbeat still names this run's fault.
  if (outcome == coordinator::StepOutcome::kNodeFault) run.node_fault = p.actuators->node_fault_text();
  // A lock-step node that faults on a command it refuses (a control mode its file does not
  // declare) answers nothing: the link times out, but the node's heartbeat says why.
  if (outcome == coordinator::StepOutcome::kLinkFailure) {
    if (std::string said = p.actuators->node_fault_text(); !said.empty()) {
      outcome = coordinator::StepOutcome::kNodeFault;
      run.node_fault = std::move(said);
    }
  }
  // A host call that failed stopped the step (its NaN command or force) or the run after it.
  if (p.host_failed()) {
    outcome = coordinator::StepOutcome::kHostCallFailed;
    run.host_error = p.host_error();
  }
  p.actuators->end_run();
  run.outcome = outcome;
  run.run_id = p.loop->run_id();
  if (outcome == coordinator::StepOutcome::kRefused) run.refusal = p.actuators->refusal_text();
  run.steps = p.steps;
  run.steps_planned = p.steps_planned;
  run.feedback_age_periods = p.loop->feedback_age_periods();
  run.limit_stop = p.loop->limit_stop();
  run.dropped_records = p.recorder->dropped();
  run.records = p.recorder->finish();
  // The last rows are written when the recorder closes its file: a failure there too means
  // the results are not whole.
  if (p.recorder->write_failed()) {
    run.write_error = p.recorder->write_error();
    if (outcome == coordinator::StepOutcome::kOk || outcome == coordinator::StepOutcome::kRecordEnded)
      run.outcome = coordinator::StepOutcome::kResultsNotWritten;
  }
  run.timing = p.timing;
  run.calibrations = p.calibrations;
  run.held_forces = p.held_forces;
  run.held_stats = p.held_stats.stats();
  run.held = p.held;
  run.operator_sender = p.operator_sender;
  run.return_to_start = p.return_to_start;
  // Command-to-feedback latency per site (each site's first channel).
  for (std::size_t i = 0; i < p.round_trips.size(); ++i) {
    p.round_trips[i].add_zeros(std::exchange(p.zero_round_trips[i], 0));
    run.timing.sites.push_back({p.actuators->sites()[i].site_id, p.round_trips[i].summary()});
  }
  run.timing.over_dds = p.actuators->over_dds();
  if (p.actuators->over_dds()) run.timing.dds_counters = p.actuators->dds_counters();
  return run;
}

}  // namespace rpsd::hybrid_test
