#include "rpsd/servo/plant_factory.h"

#include "rpsd/servo/servo_hydraulic_plant.h"

namespace rpsd::servo {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

}  // namespace

std::unique_ptr<Plant> make_plant(const PlantConfig& config) {
  return std::visit(
      Overloaded{
          [](const ServoSystemParameters& c) -> std::unique_ptr<Plant> { return std::make_unique<ServoHydraulicPlant>(c); },
          [](const PureDelayParameters& c) -> std::unique_ptr<Plant> { return std::make_unique<PureDelayPlant>(c); },
          [](const TransferFunctionPlantParameters& c) -> std::unique_ptr<Plant> {
            return std::make_unique<TransferFunctionPlant>(c);
          },
      },
      config);
}

PlantSet make_plants(const PlantConfig& config, int channels) {
  PlantSet set;
  for (int c = 0; c < channels; ++c) {
    set.owned.push_back(make_plant(config));
    set.pointers.push_back(set.owned.back().get());
  }
  return set;
}

}  // namespace rpsd::servo
