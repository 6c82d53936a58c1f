#include "rpsd/servo/channel_converters.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "rpsd/config/key_error.h"

namespace rpsd::servo {
namespace {

SignalConverterParameters read_converter(config::Source& parent, std::string_view key, std::string_view unit,
                                         std::uint64_t seed) {
  SignalConverterParameters p;
  p.seed = seed;
  const auto section = parent.optional_section(key, "a converter chain (all stages optional)");
  if (!section) return p;
  using config::Number;
  p.units_per_volt = section->number("units_per_volt", Number::positive(unit, "sensor or actuator scale per volt"));
  p.noise_rms_v = section->number_or("noise_rms_v", 0.0, Number::non_negative("V", "Gaussian noise, RMS"));
  p.saturation_v = section->number_or("saturation_v", 0.0, Number::non_negative("V", "+/- range (0: none)"));
  p.bits = static_cast<int>(section->whole_number_or("bits", 0, 30, 0, "converter resolution (0: none)"));
  p.full_scale_v =
      section->number_or("full_scale_v", 0.0, Number::non_negative("V", "converter range (0: the saturation's)"));
  section->finish();
  return p;
}

}  // namespace

bool ChannelConverters::any() const {
  return command.units_per_volt > 0.0 || displacement.units_per_volt > 0.0 || force.units_per_volt > 0.0;
}

void ChannelConverters::validate() const {
  const std::pair<const char*, const SignalConverterParameters*> named[] = {{"converters.command", &command},
                                                                            {"converters.displacement", &displacement},
                                                                            {"converters.force", &force},
                                                                            {"converters.reference", &reference},
                                                                            {"converters.error", &error}};
  for (const auto& [name, converter] : named) {
    try {
      converter->validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(name) + ": " + e.what());
    }
  }
}

void require_readable(double limit, bool rigs, const ConverterRange& range, const std::string& limit_key,
                      const std::string& converter_key, const char* unit) {
  if (range.represents(limit)) return;
  std::ostringstream message;
  if (!std::isfinite(limit)) {
    message << "none stated and the rig states none, so no limit at all, which";
  } else if (rigs) {
    message << "not stated, so the rig's " << limit << " " << unit << ", which";
  } else {
    message << limit << " " << unit;
  }
  message << " is not strictly inside what " << converter_key << " can read, " << range.low << " to " << range.high
          << " " << unit << " (a reading at its rail may stand for any value beyond it): state a limit below "
          << range.rail_magnitude() << " " << unit << " or widen " << converter_key << "'s range";
  throw config::KeyError(limit_key, message.str());
}

ChannelConverters read_channel_converters(config::Source& plant_section) {
  ChannelConverters c;
  const auto section = plant_section.optional_section("converters", "D/A and A/D converters of each channel");
  if (!section) return c;
  const auto seed = static_cast<std::uint64_t>(
      section->whole_number_or("seed", 0, 2'000'000'000, 1, "noise seed (each converter its own stream from it)"));
  c.command = read_converter(*section, "command", "m", seed);
  c.displacement = read_converter(*section, "displacement", "m", seed + 1);
  c.force = read_converter(*section, "force", "N", seed + 2);
  c.reference = read_converter(*section, "reference", "m", seed + 3);
  c.error = read_converter(*section, "error", "m", seed + 4);
  section->finish();
  return c;
}

}  // namespace rpsd::servo
