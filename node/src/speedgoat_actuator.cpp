#include "rpsd/node/speedgoat_actuator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "rpsd/node/hardware_link_checks.h"
#include "rpsd/node/owned_actuator.h"

namespace rpsd::node {

using speedgoat::ControlQuantity;
using speedgoat::DaqQuantity;
using speedgoat::get_double;
using speedgoat::put_double;
using speedgoat::Reference;

void SpeedgoatParameters::validate() const {
  check_link_channels(channels);
  Ipv4Endpoint::parse(host, port, "host");
  Ipv4Endpoint::parse(local_host, local_port, "local_host");
  if (port == 0) throw std::invalid_argument("port: required (1-65535)");
  check_link_timing(reply_timeout_s, max_missed_replies, start_timeout_s, start_tolerance_m);
  signals.validate(channels);
}

namespace {

Ipv4Endpoint validated_target(const SpeedgoatParameters& config) {
  config.validate();
  return Ipv4Endpoint::parse(config.host, config.port, "host");
}

const char* transport_name(SpeedgoatTransport t) { return t == SpeedgoatTransport::kTcp ? "TCP" : "UDP"; }

void list(std::ostream& out, const std::vector<double>& values) {
  out << "[";
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << values[i];
  out << "]";
}

}  // namespace

SpeedgoatActuator::SpeedgoatActuator(const SpeedgoatParameters& config)
    : config_(config),
      link_(config.transport, validated_target(config),
            Ipv4Endpoint::parse(config.local_host, config.local_port, "local_host"), config.signals.vector_bytes()),
      out_(config.signals.vector_bytes()),
      in_(config.signals.vector_bytes()),
      control_offset_(config.signals.control.size()),
      daq_offset_(config.signals.daq.size()),
      initial_daq_(config.signals.daq.size()) {}

SpeedgoatActuator::~SpeedgoatActuator() { end_session(); }

void SpeedgoatActuator::end_session() noexcept {
  if (!link_.connected()) return;
  const double deadline_s = monotonic_seconds() + 0.05;
  put_double(out_, speedgoat::kNewTarget, speedgoat::kEndSession);
  link_.send(out_, deadline_s);
  link_.send(out_, deadline_s);
  link_.close();
}

servo::ActuatorStatus SpeedgoatActuator::fail(const char* side, const char* reason) noexcept {
  if (!link_fault_) {
    failed_side_ = side;
    failure_ = reason;
  }
  link_fault_ = true;
  phase_ = Phase::kIdle;
  end_session();
  return servo::ActuatorStatus::kFault;
}

bool SpeedgoatActuator::compose(std::span<const double> command_m, double period_s) noexcept {
  std::array<double, servo::kMaxChannels> velocity{}, acceleration{};
  for (int c = 0; c < config_.channels; ++c) {
    if (!std::isfinite(command_m[c])) return false;
    velocity[c] = period_s > 0.0 ? (command_m[c] - previous_m_[c]) / period_s : 0.0;
    acceleration[c] = period_s > 0.0 ? (velocity[c] - previous_velocity_m_per_s_[c]) / period_s : 0.0;
  }
  const double time_s = time_s_ + period_s;
  const auto& signals = config_.signals.control;
  for (std::size_t i = 0; i < signals.size(); ++i) {
    const auto& s = signals[i];
    const double value = s.quantity == ControlQuantity::kDisplacement   ? command_m[s.channel]
                         : s.quantity == ControlQuantity::kVelocity     ? velocity[s.channel]
                         : s.quantity == ControlQuantity::kAcceleration ? acceleration[s.channel]
                         : s.quantity == ControlQuantity::kForce        ? force_command_n_[s.channel]
                         : s.quantity == ControlQuantity::kControlMode  ? control_mode_[s.channel]
                                                                        : time_s;
    const double signal = value * s.signal_per_si + control_offset_[i];
    if (!std::isfinite(signal)) return false;
    put_double(out_, speedgoat::kFirstControlSignal + static_cast<int>(i), signal);
  }
  for (int c = 0; c < config_.channels; ++c) {
    previous_m_[c] = command_m[c];
    previous_velocity_m_per_s_[c] = velocity[c];
  }
  time_s_ = time_s;
  return true;
}

SpeedgoatActuator::Step SpeedgoatActuator::send_twice(double new_target, double deadline_s) noexcept {
  put_double(out_, speedgoat::kNewTarget, new_target);
  for (int copy = 0; copy < 2; ++copy) {
    switch (link_.send(out_, deadline_s)) {
      case SpeedgoatLink::Io::kDone:
        break;
      case SpeedgoatLink::Io::kClosed:
        fail("target", "the target closed the connection");
        return Step::kFault;
      case SpeedgoatLink::Io::kTimeout:
        fail("target", "the target stopped taking vectors");
        return Step::kFault;
      case SpeedgoatLink::Io::kError:
        fail("node", "the node's socket refused to send");
        return Step::kFault;
    }
  }
  return Step::kDone;
}

SpeedgoatActuator::Step SpeedgoatActuator::receive(double deadline_s) noexcept {
  switch (link_.receive(in_, deadline_s)) {
    case SpeedgoatLink::Io::kDone:
      break;
    case SpeedgoatLink::Io::kTimeout:
      return Step::kTimeout;
    case SpeedgoatLink::Io::kClosed:
      fail("target", "the target closed the connection");
      return Step::kFault;
    case SpeedgoatLink::Io::kError:
      fail("node", "the node's socket refused to receive");
      return Step::kFault;
  }
  const double switch_pc = get_double(in_, speedgoat::kSwitchPc), at_target = get_double(in_, speedgoat::kAtTarget);
  bool well_formed = (switch_pc == 0.0 || switch_pc == 1.0) && (at_target == 0.0 || at_target == 1.0);
  const auto& daq = config_.signals.daq;
  for (std::size_t i = 0; i < daq.size(); ++i) {
    if (daq[i].quantity == DaqQuantity::kUnused) continue;
    well_formed = well_formed && std::isfinite(get_double(in_, speedgoat::kFirstDaqSignal + static_cast<int>(i)));
  }
  if (!well_formed) {
    ++counters_.malformed_vectors;
    fail("target", "a malformed vector: a flag other than 0 or 1, or a DAQ signal not finite");
    return Step::kFault;
  }
  return Step::kDone;
}

SpeedgoatActuator::Step SpeedgoatActuator::advance(double deadline_s) noexcept {
  for (;;) {
    if (phase_ == Phase::kIdle) return Step::kDone;
    const Step got = receive(deadline_s);
    if (got != Step::kDone) return got;
    const double switch_pc = get_double(in_, speedgoat::kSwitchPc);
    switch (phase_) {
      case Phase::kAwaitSwitchHigh:
        if (switch_pc != 1.0) break;
        if (const Step sent = send_twice(speedgoat::kHold, deadline_s); sent != Step::kDone) return sent;
        phase_ = Phase::kAwaitSwitchLow;
        continue;
      case Phase::kAwaitSwitchLow:
        if (switch_pc != 0.0) break;
        phase_ = Phase::kAwaitAtTarget;  // atTarget is read from the next vector on, as acquire() does
        continue;
      case Phase::kAwaitAtTarget:
        if (get_double(in_, speedgoat::kAtTarget) != 1.0) break;
        phase_ = Phase::kIdle;
        return Step::kDone;
      case Phase::kIdle:
        return Step::kDone;
    }
    ++counters_.drained_vectors;
  }
}

void SpeedgoatActuator::read_measurement(servo::ActuatorReading& reading) const noexcept {
  const auto& daq = config_.signals.daq;
  for (std::size_t i = 0; i < daq.size(); ++i) {
    const auto& d = daq[i];
    if (d.quantity == DaqQuantity::kUnused) continue;
    const double value =
        (get_double(in_, speedgoat::kFirstDaqSignal + static_cast<int>(i)) + daq_offset_[i]) / d.signal_per_si;
    (d.quantity == DaqQuantity::kDisplacement ? reading.displacement_m : reading.force_n)[d.channel] = value;
  }
}

void SpeedgoatActuator::start(std::span<const double> initial_displacement_m) {
  const int channels = config_.channels;
  if (static_cast<int>(initial_displacement_m.size()) != channels) {
    throw std::invalid_argument("SpeedgoatActuator::start: " + std::to_string(channels) +
                                " initial displacements expected, got " +
                                std::to_string(initial_displacement_m.size()));
  }
  const std::string who =
      std::string("Speedgoat target ") + transport_name(config_.transport) + " " + link_.target().to_string();
  end_session();
  link_fault_ = false;
  started_ = false;
  failed_side_ = "none";
  failure_ = "";
  consecutive_missed_ = 0;
  std::fill(out_.begin(), out_.end(), std::byte{0});
  std::fill(control_offset_.begin(), control_offset_.end(), 0.0);
  std::fill(daq_offset_.begin(), daq_offset_.end(), 0.0);
  const double deadline_s = monotonic_seconds() + config_.start_timeout_s;
  try {
    link_.connect(deadline_s);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(who + ": " + e.what());
  }
  auto check = [&](Step step, const char* what) {
    if (step == Step::kDone) return;
    std::ostringstream message;
    message << who << ": " << what << ": "
            << (step == Step::kTimeout
                    ? "no answer within start_timeout_s " + std::to_string(config_.start_timeout_s) + " s"
                    : std::string(failure_));
    end_session();
    throw std::runtime_error(message.str());
  };
  // OpenFresco's setup(): acquire() once, at the target's present position.
  phase_ = Phase::kAwaitAtTarget;
  check(advance(deadline_s), "reading the DAQ at start");
  const auto& control = config_.signals.control;
  const auto& daq = config_.signals.daq;
  for (std::size_t i = 0; i < daq.size(); ++i)
    initial_daq_[i] = get_double(in_, speedgoat::kFirstDaqSignal + static_cast<int>(i));
  // Relative control signals start where the DAQ says the piston is (in the control signal's
  // scale); the vector goes out twice with newTarget = 0, as OpenFresco sends it.
  for (std::size_t i = 0; i < control.size(); ++i) {
    const auto& s = control[i];
    if (s.reference != Reference::kRelative) continue;
    const int d = config_.signals.daq_index(s.channel, DaqQuantity::kDisplacement);
    control_offset_[i] = initial_daq_[d] / daq[d].signal_per_si * s.signal_per_si;
  }
  previous_m_ = {};
  previous_velocity_m_per_s_ = {};
  std::copy(initial_displacement_m.begin(), initial_displacement_m.end(), previous_m_.begin());
  time_s_ = 0.0;
  if (!compose(initial_displacement_m, 0.0)) {
    end_session();
    throw std::runtime_error(who + ": the initial displacement or an offset is not finite");
  }
  check(send_twice(speedgoat::kHold, deadline_s), "sending the offsets");
  for (std::size_t i = 0; i < daq.size(); ++i) {
    if (daq[i].reference == Reference::kRelative) daq_offset_[i] = -initial_daq_[i];
  }
  servo::ActuatorReading at_start;
  read_measurement(at_start);
  for (int c = 0; c < channels; ++c) {
    if (std::abs(at_start.displacement_m[c] - initial_displacement_m[c]) > config_.start_tolerance_m) {
      std::ostringstream message;
      message << who << ": channel " << c << " measures " << at_start.displacement_m[c]
              << " m (after offsets), the initial displacement is " << initial_displacement_m[c]
              << " m (start_tolerance_m " << config_.start_tolerance_m << ")";
      end_session();
      throw std::runtime_error(message.str());
    }
  }
  // "Exit the initialisation state and start the predictor-corrector": one handshake to where
  // the piston is to be, which start_tolerance_m keeps within reach.
  check(send_twice(speedgoat::kTakeTarget, deadline_s), "the first move");
  phase_ = Phase::kAwaitSwitchHigh;
  check(advance(deadline_s), "the first move");
  started_ = true;
}

bool SpeedgoatActuator::controls_force(int channel) const {
  return config_.control_mode_refusal(channel, servo::ControlMode::kForce).empty();
}

servo::ActuatorStatus SpeedgoatActuator::exchange_mixed(std::span<const double> command_m,
                                                        std::span<const double> force_command_n,
                                                        std::span<const servo::ControlMode> mode, double period_s,
                                                        servo::ActuatorReading& reading) {
  const auto n = static_cast<std::size_t>(config_.channels);
  if (force_command_n.size() != n || mode.size() != n) return fail("node", "a command of another channel count");
  for (std::size_t c = 0; c < n; ++c) {
    const bool force = mode[c] == servo::ControlMode::kForce;
    if (force && !std::isfinite(force_command_n[c])) return fail("node", "a force command that is not finite");
    // A channel with a force signal that leaves force control holds the measured force there.
    force_command_n_[c] = force ? force_command_n[c] : reading.force_n[c];
    control_mode_[c] = force ? 1.0 : 0.0;
  }
  return exchange(command_m, period_s, reading);
}

servo::ActuatorStatus SpeedgoatActuator::exchange(std::span<const double> command_m, double period_s,
                                                  servo::ActuatorReading& reading) {
  reading.fresh = false;
  if (link_fault_ || !started_) return servo::ActuatorStatus::kFault;
  if (static_cast<int>(command_m.size()) != config_.channels) return fail("node", "a command of another channel count");
  const double deadline_s = monotonic_seconds() + period_s + config_.reply_timeout_s;
  if (phase_ == Phase::kIdle) {
    if (!compose(command_m, period_s)) return fail("node", "a command that is not finite");
    if (send_twice(speedgoat::kTakeTarget, deadline_s) != Step::kDone) return servo::ActuatorStatus::kFault;
    phase_ = Phase::kAwaitSwitchHigh;
  } else {
    ++counters_.resumed_handshakes;  // this period's command waits: a half-done handshake is finished first
  }
  switch (advance(deadline_s)) {
    case Step::kFault:
      return servo::ActuatorStatus::kFault;
    case Step::kTimeout:
      ++counters_.missed_deadlines;
      if (++consecutive_missed_ > config_.max_missed_replies) {
        return fail("target", "the target did not finish a handshake in time, more than max_missed_replies in a row");
      }
      return servo::ActuatorStatus::kNoReply;
    case Step::kDone:
      break;
  }
  consecutive_missed_ = 0;
  ++counters_.handshakes;
  read_measurement(reading);
  reading.fresh = true;
  return servo::ActuatorStatus::kOk;
}

std::string SpeedgoatActuator::describe_link() const {
  std::ostringstream out;
  out << "Speedgoat target " << config_.host << ":" << config_.port << " over " << transport_name(config_.transport)
      << " (OpenFresco's handshake, " << config_.signals.vector_doubles
      << " doubles a vector; unauthenticated: the node takes vectors from this target only); offsets measured: "
         "control signals ";
  list(out, control_offset_);
  out << ", DAQ signals ";
  list(out, daq_offset_);
  out << ", DAQ at start ";
  list(out, initial_daq_);
  return out.str();
}

nlohmann::json SpeedgoatActuator::link_summary() const {
  const SpeedgoatLinkCounters& l = link_.counters();
  return {{"transport", config_.transport == SpeedgoatTransport::kTcp ? "tcp" : "udp"},
          {"target", link_.target().to_string()},
          {"vector_doubles", config_.signals.vector_doubles},
          {"offsets", {{"control", control_offset_}, {"daq", daq_offset_}, {"initial_daq", initial_daq_}}},
          {"handshakes", counters_.handshakes},
          {"vectors_sent", l.vectors_sent},
          {"vectors_received", l.vectors_received},
          {"drained_vectors", counters_.drained_vectors},
          {"resumed_handshakes", counters_.resumed_handshakes},
          {"missed_deadlines", counters_.missed_deadlines},
          {"malformed_vectors", counters_.malformed_vectors},
          {"foreign_datagrams", l.foreign_datagrams},
          {"bad_packets", l.bad_packets},
          {"send_errors", l.send_errors},
          {"receive_errors", l.receive_errors},
          {"failed_side", failed_side_},
          {"failure", failure_}};
}

SpeedgoatParameters SpeedgoatParameters::read(config::Source& section, int channels) {
  SpeedgoatParameters p;
  p.channels = channels;
  const std::string transport =
      section.choice_or("transport", {"tcp", "udp"}, "tcp", "as the target's model is built (OpenFresco's -udp)");
  p.transport = transport == "udp" ? SpeedgoatTransport::kUdp : SpeedgoatTransport::kTcp;
  p.host = section.text("host", "the target's address (dotted IPv4): the only peer the node talks to");
  p.port = static_cast<std::uint16_t>(section.whole_number("port", 1, 65535, "the target's port"));
  p.local_host = section.optional_text("local_host", "address to bind (dotted IPv4)").value_or(p.local_host);
  p.local_port = static_cast<std::uint16_t>(section.whole_number_or(
      "local_port", 0, 65535, 0, "port to bind (UDP: the one the target's model sends to; 0: any free one)"));
  p.signals = speedgoat::SignalMap::read(section, channels);
  p.reply_timeout_s = section.number_or(
      "reply_timeout_s", p.reply_timeout_s,
      {"s", "how long past the control period one command's whole handshake may take", 0.0, 60.0, true});
  p.max_missed_replies = static_cast<int>(section.whole_number_or(
      "max_missed_replies", 0, 1000, p.max_missed_replies, "consecutive late handshakes before the actuator faults"));
  p.start_timeout_s = section.number_or("start_timeout_s", p.start_timeout_s,
                                        {"s", "connecting, the offsets and the first move", 0.0, 600.0, true});
  p.start_tolerance_m = section.number_or(
      "start_tolerance_m", p.start_tolerance_m,
      config::Number::between(0.0, 1.0, "m", "largest |measured - initial| displacement start() accepts"));
  const auto rig = section.optional_section("rig", "what the rig behind the target can do (required)");
  if (!rig) {
    section.fail("rig", "a hardware node must state its rig's envelope: rig: {stroke_m, force_n, velocity_m_per_s}");
  }
  p.rig = servo::Envelope::read(*rig);
  p.signals.check(section, channels);
  check_ipv4_keys(section, {{"host", p.host}, {"local_host", p.local_host}});
  return p;
}

std::string SpeedgoatParameters::control_mode_refusal(int channel, servo::ControlMode mode) const {
  bool force_signal = false;
  for (const auto& s : signals.control) force_signal |= s.channel == channel && s.quantity == ControlQuantity::kForce;
  if (mode == servo::ControlMode::kForce && !force_signal)
    return "control_signals has no force signal for channel " + std::to_string(channel);
  if (mode != servo::ControlMode::kForce && force_signal) {
    return "control_signals has a force signal for channel " + std::to_string(channel) +
           ", which is in displacement control: declare it in force control, or take the signal out";
  }
  return {};
}

OwnedActuator SpeedgoatParameters::make(const SpeedgoatParameters& config, int) {
  OwnedActuator owned;
  owned.actuator = std::make_unique<SpeedgoatActuator>(config);
  return owned;
}

}  // namespace rpsd::node
