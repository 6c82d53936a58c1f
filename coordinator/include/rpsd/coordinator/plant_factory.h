// A simulated plant from its typed configuration (the scenario's or a servo node's
// `servo:` section). Not real-time safe.
#pragma once

#include <memory>

#include "rpsd/scenarios/test_scenario.h"
#include "rpsd/servo/plant.h"

namespace rpsd::coordinator {

std::unique_ptr<servo::Plant> make_plant(const scenarios::PlantConfig& config);

}  // namespace rpsd::coordinator
