#include "rpsd/studies/converter_rails.h"

#include <cmath>
#include <type_traits>

namespace rpsd::studies {

double converter_rail(const servo::SignalConverterParameters& p) {
  const servo::ConverterRange range = p.range();  // where the converter clamps, bit for bit
  return std::fmin(std::abs(range.low), std::abs(range.high));
}

ConverterRails converter_rails(const servo::PlantConfig& plant) {
  return std::visit(
      [](const auto& p) {
        ConverterRails rails;
        using P = std::decay_t<decltype(p)>;
        if constexpr (!std::is_same_v<P, servo::FeedbackControlledPlantParameters>) {
          rails.command_m = converter_rail(p.converters.command);
        }
        rails.displacement_m = converter_rail(p.converters.displacement);
        rails.force_n = converter_rail(p.converters.force);
        return rails;
      },
      plant);
}

}  // namespace rpsd::studies
