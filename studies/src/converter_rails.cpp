#include "rpsd/studies/converter_rails.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace rpsd::studies {

double converter_rail(const servo::SignalConverterParameters& p) {
  if (p.units_per_volt == 0.0) return servo::Envelope::kNone;  // no voltage stages: passes unchanged
  double volts = p.saturation_v > 0.0 ? p.saturation_v : servo::Envelope::kNone;
  if (p.bits > 0) {
    // SignalConverter's codes: -2^(bits-1) .. 2^(bits-1) - 1 of step 2 full_scale / 2^bits,
    // limited to the largest step inside the saturation band.
    const double full_scale_v = p.full_scale_v > 0.0 ? p.full_scale_v : p.saturation_v;
    const double step_v = 2.0 * full_scale_v / std::ldexp(1.0, p.bits);
    double codes = std::ldexp(1.0, p.bits - 1) - 1.0;  // the smaller side, positive
    if (p.saturation_v > 0.0) {
      double inside = std::floor(p.saturation_v / step_v);
      while (inside > 0.0 && inside * step_v > p.saturation_v) inside -= 1.0;
      codes = std::min(codes, inside);
    }
    volts = codes * step_v;
  }
  return volts * std::abs(p.units_per_volt);
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
