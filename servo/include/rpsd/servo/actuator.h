// The servo node's view of its actuators: one interface for the simulated plants and for
// hardware adapters alike (ros2_control's hardware_interface pattern), so that the node's
// control loop, limits and watchdog cannot tell them apart. Adding an adapter (a vendor API,
// another controller protocol) means one new class behind this interface and nothing else.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace rpsd::servo {

// Channels an actuator may have (the node's messages carry as many).
inline constexpr int kMaxChannels = 8;

enum class ActuatorStatus : std::uint8_t {
  kOk,       // the command was applied and `reading` holds the new measurement
  kNoReply,  // the hardware did not answer in time: reading.fresh = false, values kept
  kFault,    // the actuator cannot follow commands (interlock, lost link, bad command)
};

const char* actuator_status_name(ActuatorStatus status);

// How a channel is driven (mixed control, issue 30): following a displacement command, or
// holding a force command measured by its load cell.
enum class ControlMode : std::uint8_t { kDisplacement, kForce };
const char* control_mode_name(ControlMode mode);

// The sensors of every channel at the end of one control period.
struct ActuatorReading {
  std::array<double, kMaxChannels> displacement_m{};
  std::array<double, kMaxChannels> force_n{};
  bool fresh = true;             // false when this period brought no new measurement
  bool at_end_stop = false;      // a piston is at the end of its stroke
  bool valve_saturated = false;  // a servovalve is fully open
};

class Actuator {
 public:
  virtual ~Actuator() = default;

  // Number of channels, fixed at construction (1..kMaxChannels).
  virtual int channels() const = 0;

  // Connects, homes or resets the actuator so that it holds initial_displacement_m (one
  // value per channel). Throws with a message naming what failed. Not real-time safe.
  virtual void start(std::span<const double> initial_displacement_m) = 0;

  // Applies command_m (one value per channel) over the coming control period of period_s,
  // the command ramping from the previous one, and returns the measurement at the end of
  // that period in `reading`. On kNoReply the values in `reading` are left untouched and
  // reading.fresh is false. Real-time safe: no allocation, no locks, no exceptions.
  virtual ActuatorStatus exchange(std::span<const double> command_m, double period_s, ActuatorReading& reading) = 0;

  // Mixed control: as exchange(), but a channel whose mode is kForce holds force_command_n[c]
  // (newtons, ramping from its previous force command; from the measured force when it has
  // just entered force control) and ignores command_m[c]; a channel back in displacement
  // control starts from its measured displacement. One value of each span per channel. The
  // default serves displacement only: every channel in kDisplacement calls exchange(), any
  // kForce channel is a kFault. Real-time safe.
  virtual ActuatorStatus exchange_mixed(std::span<const double> command_m, std::span<const double> force_command_n,
                                        std::span<const ControlMode> mode, double period_s, ActuatorReading& reading);

  // Whether channel c can be driven in force control; the node refuses a node file that puts a
  // channel in force control otherwise. Not real-time safe.
  virtual bool controls_force(int /*channel*/) const { return false; }

  // After a kFault: what failed, in the lab controller's own words when it gave any ("the
  // target stopped answering", a site's refusal); empty when there is nothing to add. The
  // view stays valid until the next exchange() or start(). Real-time safe.
  virtual std::string_view fault_text() const noexcept { return {}; }
};

}  // namespace rpsd::servo
