// A simulated plant from its typed configuration (the scenario's or a servo node's
// `servo:` section). Not real-time safe.
#pragma once

#include <memory>
#include <vector>

#include "rpsd/scenarios/test_scenario.h"
#include "rpsd/servo/plant.h"

namespace rpsd::coordinator {

std::unique_ptr<servo::Plant> make_plant(const scenarios::PlantConfig& config);

/// One plant per channel, all of one configuration, with the pointers an actuator borrows.
struct PlantSet {
  std::vector<std::unique_ptr<servo::Plant>> owned;
  std::vector<servo::Plant*> pointers;
};
PlantSet make_plants(const scenarios::PlantConfig& config, int channels);

}  // namespace rpsd::coordinator
