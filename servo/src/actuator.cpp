#include "rpsd/servo/actuator.h"

namespace rpsd::servo {

const char* actuator_status_name(ActuatorStatus status) {
  switch (status) {
    case ActuatorStatus::kOk:
      return "ok";
    case ActuatorStatus::kNoReply:
      return "no reply";
    case ActuatorStatus::kFault:
      return "fault";
  }
  return "unknown";
}

const char* control_mode_name(ControlMode mode) {
  switch (mode) {
    case ControlMode::kDisplacement:
      return "displacement";
    case ControlMode::kForce:
      return "force";
  }
  return "unknown";
}

ActuatorStatus Actuator::exchange_mixed(std::span<const double> command_m, std::span<const double> /*force_command_n*/,
                                        std::span<const ControlMode> mode, double period_s, ActuatorReading& reading) {
  for (ControlMode m : mode) {
    if (m != ControlMode::kDisplacement) return ActuatorStatus::kFault;
  }
  return exchange(command_m, period_s, reading);
}

}  // namespace rpsd::servo
