// The simulated plants rpsd knows, in one place: their configurations as one variant, and the
// plant each configuration builds. A new plant is its own files plus one line here and one
// in plant_factory.cpp (CONTRIBUTING.md). Not real-time safe.
#pragma once

#include <memory>
#include <variant>
#include <vector>

#include "rpsd/servo/plant.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_parameters.h"
#include "rpsd/servo/transfer_function_plant.h"

namespace rpsd::servo {

// The actuator of a channel: the seed paper's servo-hydraulic model, an ideal delay, or a
// transfer function from command to displacement.
using PlantConfig = std::variant<ServoSystemParameters, PureDelayParameters, TransferFunctionPlantParameters>;

std::unique_ptr<Plant> make_plant(const PlantConfig& config);

// One plant per channel, all of one configuration, with the pointers an actuator borrows.
struct PlantSet {
  std::vector<std::unique_ptr<Plant>> owned;
  std::vector<Plant*> pointers;
};
PlantSet make_plants(const PlantConfig& config, int channels);

}  // namespace rpsd::servo
