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

}  // namespace rpsd::coordinator
