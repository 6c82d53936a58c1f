// An actuator with whatever it borrows (the simulated plants), owned together.
#pragma once

#include <memory>

#include "rpsd/servo/actuator.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::node {

struct OwnedActuator {
  servo::PlantSet plants;  // empty for hardware
  std::unique_ptr<servo::Actuator> actuator;
};

}  // namespace rpsd::node
