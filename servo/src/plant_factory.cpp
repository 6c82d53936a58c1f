#include "rpsd/servo/plant_factory.h"

#include "rpsd/servo/converted_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"

#include <stdexcept>
#include <type_traits>

namespace rpsd::servo {

std::unique_ptr<Plant> make_plant(const PlantConfig& config) {
  return std::visit(
      [](const auto& p) -> std::unique_ptr<Plant> {
        auto plant = std::make_unique<typename std::decay_t<decltype(p)>::Model>(p);
        // A servo loop has its converters inside the loop; any other plant behind them.
        if constexpr (!std::is_same_v<std::decay_t<decltype(p)>, FeedbackControlledPlantParameters>) {
          if (p.converters.any()) return std::make_unique<ConvertedPlant>(std::move(plant), p.converters);
        }
        return plant;
      },
      config);
}

PlantConfig read_plant_config(config::Source& section, double specimen_stiffness_n_per_m) {
  const std::string kind = section.choice("kind", PlantKinds::names(), "the plant");
  PlantConfig plant = *PlantKinds::read(kind, section, specimen_stiffness_n_per_m);
  // Every kind's converters, read alike (a servo loop's sit inside its loop: make_plant).
  std::visit(
      [&section](auto& p) {
        p.converters = read_channel_converters(section);
        // Only a servo loop has a reference and an error of its own to convert (a listing, whose
        // has() says no to every key, lists on).
        if (!std::is_same_v<std::decay_t<decltype(p)>, FeedbackControlledPlantParameters> &&
            p.converters.any_in_loop() && section.has("kind")) {
          section.fail("converters", "reference and error: only a servo loop (kind feedback_controlled) has them");
        }
        try {
          p.converters.validate();
        } catch (const std::invalid_argument& e) {
          section.fail("converters", e.what());
        }
      },
      plant);
  section.finish();
  return plant;
}

void check_control_period(const PlantConfig& config, double control_period_s) {
  if (const auto* controlled = std::get_if<FeedbackControlledPlantParameters>(&config)) {
    controlled->validate_for_period(control_period_s);
  }
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

ReadingRanges reading_ranges_of(const PlantConfig& config) {
  return std::visit([](const auto& p) { return p.converters.reading_ranges(); }, config);
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
