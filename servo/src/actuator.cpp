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

}  // namespace rpsd::servo
