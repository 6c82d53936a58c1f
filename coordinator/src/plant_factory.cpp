#include "rpsd/coordinator/plant_factory.h"

#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/transfer_function_plant.h"

namespace rpsd::coordinator {

std::unique_ptr<servo::Plant> make_plant(const scenarios::PlantConfig& config) {
  return std::visit(
      [](const auto& c) -> std::unique_ptr<servo::Plant> {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, servo::ServoSystemParameters>) return std::make_unique<servo::ServoHydraulicPlant>(c);
        else if constexpr (std::is_same_v<C, servo::PureDelayParameters>) return std::make_unique<servo::PureDelayPlant>(c);
        else return std::make_unique<servo::TransferFunctionPlant>(c);
      },
      config);
}

PlantSet make_plants(const scenarios::PlantConfig& config, int channels) {
  PlantSet set;
  for (int c = 0; c < channels; ++c) {
    set.owned.push_back(make_plant(config));
    set.pointers.push_back(set.owned.back().get());
  }
  return set;
}

}  // namespace rpsd::coordinator
