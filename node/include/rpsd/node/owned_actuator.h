// An actuator with whatever it borrows (the simulated plants), owned together.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>

#include "rpsd/servo/actuator.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::node {

struct OwnedActuator {
  servo::PlantSet plants;  // empty for hardware
  std::unique_ptr<servo::Actuator> actuator;
};

// The simulated plants' sensors as they read now, without advancing them (after start(): at
// rest); nullopt for hardware, which is read only by an exchange. Not real-time safe.
inline std::optional<servo::ActuatorReading> reading_at_rest(const OwnedActuator& owned) {
  if (owned.plants.pointers.empty()) return std::nullopt;
  servo::ActuatorReading reading;
  for (std::size_t c = 0; c < owned.plants.pointers.size() && c < reading.displacement_m.size(); ++c) {
    const servo::PlantMeasurement m = owned.plants.pointers[c]->measure();
    reading.displacement_m[c] = m.displacement_m;
    reading.force_n[c] = m.force_n;
    reading.at_end_stop = reading.at_end_stop || m.at_end_stop;
    reading.valve_saturated = reading.valve_saturated || m.valve_saturated;
  }
  return reading;
}

}  // namespace rpsd::node
