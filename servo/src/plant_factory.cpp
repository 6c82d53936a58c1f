#include "rpsd/servo/plant_factory.h"

#include "rpsd/servo/servo_hydraulic_plant.h"

namespace rpsd::servo {

std::unique_ptr<Plant> make_plant(const PlantConfig& config) {
  return std::visit(
      [](const auto& p) -> std::unique_ptr<Plant> {
        return std::make_unique<typename std::decay_t<decltype(p)>::Model>(p);
      },
      config);
}

PlantConfig read_plant_config(config::Source& section, double specimen_stiffness_n_per_m) {
  const std::string kind = section.choice("kind", PlantKinds::names(), "the plant");
  const PlantConfig plant = *PlantKinds::read(kind, section, specimen_stiffness_n_per_m);
  section.finish();
  return plant;
}

Envelope envelope_of(const PlantConfig& config) {
  return std::visit(
      [](const auto& p) -> Envelope {
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, ServoSystemParameters>) {
          return p.envelope();
        } else if constexpr (std::is_same_v<std::decay_t<decltype(p)>, FeedbackControlledPlantParameters>) {
          return p.rig();
        } else {
          return p.rig;
        }
      },
      config);
}

double specimen_stiffness_of(const PlantConfig& config) {
  return std::visit(
      [](const auto& p) -> double {
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, ServoSystemParameters>) {
          return p.specimen.stiffness.initial_n_per_m;
        } else if constexpr (std::is_same_v<std::decay_t<decltype(p)>, FeedbackControlledPlantParameters>) {
          return p.plant.specimen_stiffness_n_per_m;
        } else {
          return p.specimen_stiffness_n_per_m;
        }
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
