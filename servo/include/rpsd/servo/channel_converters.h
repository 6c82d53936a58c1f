// A channel's converters: the D/A that carries the command to the rig and the A/D converters
// behind its displacement sensor and load cell (signal_converter.h), each off unless stated.
// Any plant can have them (servo.converters); a servo loop (feedback_controlled_plant.h) has
// them inside the loop, where its controller reads and writes through them.
#pragma once

#include <string>

#include "rpsd/config/source.h"
#include "rpsd/servo/signal_converter.h"

namespace rpsd::servo {

// What a channel's readings can show: the displacement's A/D range in m and the force's in N
// (their rails; infinite without a converter).
struct ReadingRanges {
  ConverterRange displacement_m;
  ConverterRange force_n;
};

struct ChannelConverters {
  SignalConverterParameters command;       // D/A, m
  SignalConverterParameters displacement;  // displacement sensor and A/D, m
  SignalConverterParameters force;         // load cell and A/D, N
  // A servo loop's own signals (feedback_controlled only): the command as its controller
  // receives it (the reference r, e.g. G_T's output) and the tracking error r - x_m fed to
  // the controller, each in m; the RTHS benchmark quantises and saturates both.
  SignalConverterParameters reference;
  SignalConverterParameters error;

  // Any of command, displacement and force (the converters of any plant).
  bool any() const;
  // The reference's or the error's converter is stated.
  bool any_in_loop() const { return reference.units_per_volt > 0.0 || error.units_per_volt > 0.0; }
  // Each converter's own check, its name in the message ("converters.force: ...").
  void validate() const;
  // The readings' converters' rails (the command's D/A is no reading).
  ReadingRanges reading_ranges() const { return {displacement.range(), force.range()}; }
};

// The one rule where a limit meets a converter: a limit on a reading (|value| <= limit) must
// lie strictly inside what the reading's converter can represent, or a reading at the rail
// could hide any value beyond the limit. Otherwise config::KeyError at limit_key ("limit_key: ...") naming
// converter_key too, and saying whether the limit was the rig's (`rigs`: none stated). `unit`:
// "m" or "N". Not real-time safe.
void require_readable(double limit, bool rigs, const ConverterRange& range, const std::string& limit_key,
                      const std::string& converter_key, const char* unit);

// The optional `converters` section of a plant: `seed` and `command`, `displacement`, `force`,
// `reference`, `error`, each converter with its own noise stream (seed, seed + 1, ... seed + 4).
// Checked by validate().
ChannelConverters read_channel_converters(config::Source& plant_section);

}  // namespace rpsd::servo
