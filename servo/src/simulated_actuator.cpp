#include "rpsd/servo/simulated_actuator.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::servo {

namespace {

// Channel c's sensors into the reading; an end stop or a saturated valve on any channel counts.
void add_measurement(const PlantMeasurement& m, int c, ActuatorReading& reading) {
  reading.displacement_m[static_cast<std::size_t>(c)] = m.displacement_m;
  reading.force_n[static_cast<std::size_t>(c)] = m.force_n;
  reading.at_end_stop = reading.at_end_stop || m.at_end_stop;
  reading.valve_saturated = reading.valve_saturated || m.valve_saturated;
}

}  // namespace

SimulatedActuator::SimulatedActuator(std::span<Plant* const> plants) : channels_(static_cast<int>(plants.size())) {
  if (plants.empty() || plants.size() > kMaxChannels) {
    throw std::invalid_argument("SimulatedActuator: between 1 and " + std::to_string(kMaxChannels) +
                                " plants (one per channel), got " + std::to_string(plants.size()));
  }
  for (int c = 0; c < channels_; ++c) {
    if (plants[c] == nullptr)
      throw std::invalid_argument("SimulatedActuator: plant of channel " + std::to_string(c) + " is null");
    plants_[c] = plants[c];
    force_plants_[c] = dynamic_cast<ForceControlledPlant*>(plants[c]);
  }
}

bool SimulatedActuator::controls_force(int channel) const {
  return channel >= 0 && channel < channels_ && force_plants_[channel] != nullptr &&
         force_plants_[channel]->controls_force();
}

void SimulatedActuator::start(std::span<const double> initial_displacement_m) {
  if (static_cast<int>(initial_displacement_m.size()) != channels_) {
    throw std::invalid_argument("SimulatedActuator::start: " + std::to_string(channels_) +
                                " initial displacements expected, got " +
                                std::to_string(initial_displacement_m.size()));
  }
  for (double x : initial_displacement_m) {
    if (!std::isfinite(x)) throw std::invalid_argument("SimulatedActuator::start: initial displacement is not finite");
  }
  reset(initial_displacement_m);
}

void SimulatedActuator::reset(std::span<const double> displacement_m) {
  for (int c = 0; c < channels_; ++c) {
    const double x0 = c < static_cast<int>(displacement_m.size()) ? displacement_m[c] : 0.0;
    plants_[c]->reset(x0);
    last_command_m_[c] = x0;
    last_mode_[c] = ControlMode::kDisplacement;
    last_force_n_[c] = 0.0;
  }
}

ActuatorStatus SimulatedActuator::exchange(std::span<const double> command_m, double period_s,
                                           ActuatorReading& reading) {
  if (static_cast<int>(command_m.size()) != channels_ || !(period_s > 0.0) || !std::isfinite(period_s))
    return ActuatorStatus::kFault;
  for (int c = 0; c < channels_; ++c) {
    if (!std::isfinite(command_m[c])) return ActuatorStatus::kFault;
  }
  reading.at_end_stop = reading.valve_saturated = false;
  for (int c = 0; c < channels_; ++c) {
    if (last_mode_[c] != ControlMode::kDisplacement) {
      // Back from force control: the ramp starts where the piston is.
      last_command_m_[c] = plants_[c]->measure().displacement_m;
      last_mode_[c] = ControlMode::kDisplacement;
    }
    plants_[c]->advance(last_command_m_[c], command_m[c], period_s);
    last_command_m_[c] = command_m[c];
    add_measurement(plants_[c]->measure(), c, reading);
  }
  reading.fresh = true;
  return ActuatorStatus::kOk;
}

ActuatorStatus SimulatedActuator::exchange_mixed(std::span<const double> command_m,
                                                 std::span<const double> force_command_n,
                                                 std::span<const ControlMode> mode, double period_s,
                                                 ActuatorReading& reading) {
  const auto n = static_cast<std::size_t>(channels_);
  if (command_m.size() != n || force_command_n.size() != n || mode.size() != n || !(period_s > 0.0) ||
      !std::isfinite(period_s))
    return ActuatorStatus::kFault;
  bool any_force = false;
  for (int c = 0; c < channels_; ++c) {
    if (mode[c] == ControlMode::kForce) {
      if (!controls_force(c) || !std::isfinite(force_command_n[c])) return ActuatorStatus::kFault;
      any_force = true;
    } else if (mode[c] != ControlMode::kDisplacement) {
      return ActuatorStatus::kFault;
    }
  }
  // Every channel in displacement control: exactly the displacement path.
  if (!any_force) return exchange(command_m, period_s, reading);
  for (int c = 0; c < channels_; ++c) {
    if (mode[c] == ControlMode::kDisplacement && !std::isfinite(command_m[c])) return ActuatorStatus::kFault;
  }
  reading.at_end_stop = reading.valve_saturated = false;
  for (int c = 0; c < channels_; ++c) {
    if (mode[c] == ControlMode::kForce) {
      // Entering force control: the ramp starts from the force the load cell reads.
      if (last_mode_[c] != ControlMode::kForce) last_force_n_[c] = plants_[c]->measure().force_n;
      force_plants_[c]->advance_in_force(last_force_n_[c], force_command_n[c], period_s);
      last_force_n_[c] = force_command_n[c];
      last_mode_[c] = ControlMode::kForce;
    } else {
      if (last_mode_[c] != ControlMode::kDisplacement) last_command_m_[c] = plants_[c]->measure().displacement_m;
      plants_[c]->advance(last_command_m_[c], command_m[c], period_s);
      last_command_m_[c] = command_m[c];
      last_mode_[c] = ControlMode::kDisplacement;
    }
    add_measurement(plants_[c]->measure(), c, reading);
  }
  reading.fresh = true;
  return ActuatorStatus::kOk;
}

ActuatorReading SimulatedActuator::measure() const {
  ActuatorReading reading;
  for (int c = 0; c < channels_; ++c) {
    const PlantMeasurement m = plants_[c]->measure();
    reading.displacement_m[c] = m.displacement_m;
    reading.force_n[c] = m.force_n;
  }
  return reading;
}

}  // namespace rpsd::servo
