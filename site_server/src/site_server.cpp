#include "rpsd/site_server/site_server.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/hybrid_test/actuator_links.h"
#include "rpsd/realtime/realtime_setup.h"
#include "rpsd/servo/envelope.h"

namespace rpsd::site_server {

SiteServer::SiteServer(const SiteServerConfig& config, const std::filesystem::path& csv) : config_(config) {
  const hybrid_test::TestConfig& site = config_.site;
  const int channels = static_cast<int>(site.experimental.size());
  const int n = config_.element_dofs;
  control_period_s_ = 1.0 / site.control_rate_hz;

  coordinator::ExchangeParts parts;
  parts.compensators.resize(static_cast<std::size_t>(channels));
  parts.force_paths.resize(static_cast<std::size_t>(channels));
  parts.limits.resize(static_cast<std::size_t>(channels));
  for (const auto& channel : site.experimental) {
    const auto ch = static_cast<std::size_t>(channel.dof.actuator_channel);
    compensators_.push_back(compensation::make_compensator(site.compensation, control_period_s_));
    parts.compensators[ch] = compensators_.back().get();
    parts.limits[ch] = coordinator::within_envelope(channel.limits, servo::envelope_of(site.plant), control_period_s_);
    parts.force_paths[ch] = {channel.restoring_force, channel.dof.specimen_stiffness_estimate_n_per_m};
  }
  // At rest at zero: OpenSees starts its analysis from its model's unloaded state.
  targets_ = Eigen::VectorXd::Zero(channels);
  const std::uint64_t run_id = transport::draw_run_id();
  actuators_ = std::make_unique<hybrid_test::ActuatorLinks>(
      site, control_period_s_, false, std::span<const double>(targets_.data(), static_cast<std::size_t>(channels)),
      run_id);
  parts.link = &actuators_->link();
  parts.test_id = site.transport.test_id;
  parts.run_id = run_id;
  parts.stop_on_node_limits = true;
  parts.max_valve_saturation_exchanges =
      std::max(1, static_cast<int>(std::lround(site.run_away.max_valve_saturation_s / control_period_s_)));
  exchange_ = std::make_unique<coordinator::ExperimentalExchange>(std::move(parts));
  std::vector<double> force0(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    force0[static_cast<std::size_t>(c)] = actuators_->initial_force_n(c);
  }
  exchange_->start(targets_, force0);
  for (auto* v : {&trial_d_, &trial_v_, &trial_a_, &basic_force_}) *v = Eigen::VectorXd::Zero(n);
  run_.run_id = run_id;
  run_.peak_measured_m.assign(static_cast<std::size_t>(channels), 0.0);
  run_.peak_force_n.assign(static_cast<std::size_t>(channels), 0.0);
  coordinator::RecorderOptions recording;
  recording.keep_records = false;
  recording.idle_poll = coordinator::paced_idle_poll(control_period_s_);  // paced by its client
  recorder_ =
      std::make_unique<coordinator::Recorder>(csv, channels, std::min(n, coordinator::kMaxRecordedDofs), recording);
}

SiteServer::~SiteServer() = default;

double SiteServer::reference_of(std::size_t channel) const {
  const int relative_to = config_.maps[channel].relative_to;
  return relative_to >= 0 ? trial_d_[relative_to] : 0.0;
}

bool SiteServer::stop(coordinator::StepOutcome outcome) {
  stopped_ = true;
  run_.outcome = outcome;
  run_.limit_stop = exchange_->limit_stop();
  return false;
}

bool SiteServer::set_trial(std::span<const double> displacement, std::span<const double> velocity,
                           std::span<const double> acceleration, double time_s) {
  if (stopped_) return false;
  // One command per OpenSees step, at the site's control period: the actuators' dynamics run
  // on that clock, so a step of another length would test another structure. A trial is of
  // the step under way (the same time: a repeated or iterated trial) or of the next (one
  // period later); any other time, backwards included, is refused before it is commanded.
  const double dt = time_s - step_time_s_;
  const double tolerance_s = 1e-6 * control_period_s_;
  if (std::abs(dt - control_period_s_) <= tolerance_s) {
    step_time_s_ = time_s;
  } else if (std::abs(dt) > tolerance_s) {
    std::ostringstream text;
    text.precision(9);
    if (dt < 0.0) {
      text << "OpenSees' trial time went back " << -dt << " s (from t = " << step_time_s_ << " s to " << time_s
           << " s): a trial is of the step under way or of the next, " << control_period_s_
           << " s later (clock.control_rate_hz " << config_.site.control_rate_hz << "); it was not commanded";
    } else {
      text << "OpenSees stepped " << dt << " s (from t = " << step_time_s_ << " s to " << time_s
           << " s) but the site commands its actuators every " << control_period_s_ << " s (clock.control_rate_hz "
           << config_.site.control_rate_hz << "): give the OpenSees analysis dt = " << control_period_s_
           << " or the site control_rate_hz = " << 1.0 / dt;
    }
    run_.stop_text = text.str();
    return stop(coordinator::StepOutcome::kRefused);
  }
  // A trial that moves nothing is not another command: an explicit scheme sends each step's
  // displacements twice (NewmarkExplicit: predictor, then corrector with new velocities;
  // CentralDifference: the new ones stamped with the old time, then again with the new),
  // and commanding both would drive the actuators two control periods per step.
  bool moved = !commanded_;  // the first trial is a command even at rest: the steps line up with OpenSees'
  for (int i = 0; i < config_.element_dofs; ++i) moved |= trial_d_[i] != displacement[static_cast<std::size_t>(i)];
  for (int i = 0; i < config_.element_dofs; ++i) {
    trial_d_[i] = displacement[static_cast<std::size_t>(i)];
    trial_v_[i] = velocity[static_cast<std::size_t>(i)];
    trial_a_[i] = acceleration[static_cast<std::size_t>(i)];
  }
  trial_time_s_ = time_s;
  pending_ = pending_ || moved;
  return true;
}

bool SiteServer::force(std::span<double> force) {
  if (stopped_) return false;
  if (pending_) {
    pending_ = false;
    commanded_ = true;
    for (std::size_t ch = 0; ch < config_.maps.size(); ++ch) {
      targets_[static_cast<Eigen::Index>(ch)] = config_.site.experimental[ch].dof.displacement_scale *
                                                (trial_d_[config_.maps[ch].basic_dof] - reference_of(ch));
    }
    const coordinator::StepOutcome outcome = exchange_->exchange(targets_, trial_time_s_);
    if (outcome != coordinator::StepOutcome::kOk) return stop(outcome);
    basic_force_.setZero();
    const Eigen::VectorXd& specimen = exchange_->specimen_forces();
    for (std::size_t ch = 0; ch < config_.maps.size(); ++ch) {
      const ChannelMap& map = config_.maps[ch];
      const double f = config_.site.experimental[ch].dof.force_scale * specimen[static_cast<Eigen::Index>(ch)];
      basic_force_[map.basic_dof] += f;
      if (map.relative_to >= 0) basic_force_[map.relative_to] -= f;
      run_.peak_measured_m[ch] = std::max(run_.peak_measured_m[ch], std::abs(exchange_->feedback().displacement_m[ch]));
      run_.peak_force_n[ch] = std::max(run_.peak_force_n[ch], std::abs(exchange_->feedback().force_n[ch]));
    }
    ++run_.exchanges;
    record_.step = run_.exchanges;
    record_.time_s = trial_time_s_;
    exchange_->fill_channels(record_);
    record_.dofs = static_cast<std::uint8_t>(std::min(config_.element_dofs, coordinator::kMaxRecordedDofs));
    for (int i = 0; i < record_.dofs; ++i) {
      record_.displacement_m[i] = trial_d_[i];
      record_.velocity_m_per_s[i] = trial_v_[i];
      record_.acceleration_m_per_s2[i] = trial_a_[i];
      record_.restoring_force_n[i] = basic_force_[i];
    }
    recorder_->record_or_wait(record_);
    if (recorder_->write_failed()) return stop(coordinator::StepOutcome::kResultsNotWritten);
  }
  for (int i = 0; i < config_.element_dofs; ++i) force[static_cast<std::size_t>(i)] = basic_force_[i];
  return true;
}

void SiteServer::measured_displacement(std::span<double> displacement) {
  for (int i = 0; i < config_.element_dofs; ++i) displacement[static_cast<std::size_t>(i)] = trial_d_[i];
  for (std::size_t ch = 0; ch < config_.maps.size(); ++ch) {
    displacement[static_cast<std::size_t>(config_.maps[ch].basic_dof)] =
        exchange_->feedback().displacement_m[ch] / config_.site.experimental[ch].dof.displacement_scale +
        reference_of(ch);
  }
}

void SiteServer::stiffness(std::span<double> matrix) {
  // The specimens' estimates, each on its channel's DOFs: k (e_dof - e_relative)(...)^T.
  const auto n = static_cast<std::size_t>(config_.element_dofs);
  std::fill(matrix.begin(), matrix.end(), 0.0);
  for (std::size_t ch = 0; ch < config_.maps.size(); ++ch) {
    const auto& dof = config_.site.experimental[ch].dof;
    const double k = dof.force_scale * dof.displacement_scale * dof.specimen_stiffness_estimate_n_per_m;
    const ChannelMap& map = config_.maps[ch];
    const auto i = static_cast<std::size_t>(map.basic_dof);
    matrix[i * n + i] += k;
    if (map.relative_to >= 0) {
      const auto j = static_cast<std::size_t>(map.relative_to);
      matrix[j * n + j] += k;
      matrix[i * n + j] -= k;
      matrix[j * n + i] -= k;
    }
  }
}

void SiteServer::commit() { ++run_.commits; }

opensees::SessionOptions SiteServer::session_options(const opensees::StopRequest& stop) const {
  opensees::SessionOptions options;
  options.basic_dofs = config_.element_dofs;
  options.idle_timeout_s = config_.idle_timeout_s;
  options.message_timeout_s = config_.message_timeout_s;
  options.stop = stop;
  return options;
}

SiteRun SiteServer::serve(opensees::TcpStream stream, const opensees::StopRequest& stop) {
  opensees::GenericClientSession session(std::move(stream), session_options(stop));
  return serve(session);
}

SiteRun SiteServer::serve(opensees::GenericClientSession& session) {
  // A lock-step exchange with another process: each request wakes this one from idle, which is
  // slow unless the CPUs are kept awake (docs/dds-transport.md; clock.keep_cpus_awake).
  realtime::RealTimeSetupReport awake;
  const realtime::CpuWakeLatencyHold cpus_awake = realtime::hold_cpus_awake(config_.site.clock.realtime, awake);
  run_.end = session.serve(*this);
  run_.client_sizes = session.sizes().text();
  run_.drained = session.drained();
  actuators_->end_run();
  recorder_->finish();
  run_.write_error = recorder_->write_error();
  return run_;
}

}  // namespace rpsd::site_server
