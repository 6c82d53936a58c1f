// Simulated actuators: one Plant per channel (the paper's servo-hydraulic model, a transfer
// function, an ideal delay) behind the Actuator interface. Between two commands each
// channel's command ramps linearly from the previous value to the new one (first-order
// hold), as a ramp generator in front of a servo controller does.
#pragma once

#include <array>
#include <span>

#include "rpsd/servo/actuator.h"
#include "rpsd/servo/force_controlled_plant.h"
#include "rpsd/servo/plant.h"

namespace rpsd::servo {

class SimulatedActuator final : public Actuator {
 public:
  // `plants` are not owned and must outlive the actuator; 1..kMaxChannels, none
  // null. Throws std::invalid_argument. Not real-time safe.
  explicit SimulatedActuator(std::span<Plant* const> plants);

  int channels() const override { return channels_; }

  // Requires one value per channel (throws std::invalid_argument), then reset(). Not
  // real-time safe.
  void start(std::span<const double> initial_displacement_m) override;

  // Puts every plant at rest at its initial displacement (missing values: 0) and makes
  // that the previous command. Real-time safe.
  void reset(std::span<const double> displacement_m);

  // kFault (nothing advanced) when the command has the wrong channel count, a non-finite
  // value, or the period is not positive and finite. Real-time safe.
  ActuatorStatus exchange(std::span<const double> command_m, double period_s, ActuatorReading& reading) override;
  // Mixed control: a force channel's plant advances in force control (ForceControlledPlant); a
  // channel entering force control ramps from its measured force, one leaving it from its
  // measured displacement. kFault as exchange(), and for a force channel whose plant has no
  // force loop. Real-time safe.
  ActuatorStatus exchange_mixed(std::span<const double> command_m, std::span<const double> force_command_n,
                                std::span<const ControlMode> mode, double period_s, ActuatorReading& reading) override;
  // Channel c's plant is a ForceControlledPlant with a force loop.
  bool controls_force(int channel) const override;

  // The plants' current sensor readings, without advancing. Real-time safe.
  ActuatorReading measure() const;

 private:
  std::array<Plant*, kMaxChannels> plants_{};
  std::array<double, kMaxChannels> last_command_m_{};
  std::array<ForceControlledPlant*, kMaxChannels> force_plants_{};  // null: no force control
  std::array<ControlMode, kMaxChannels> last_mode_{};
  std::array<double, kMaxChannels> last_force_n_{};  // a force channel's previous force command
  int channels_ = 0;
};

}  // namespace rpsd::servo
