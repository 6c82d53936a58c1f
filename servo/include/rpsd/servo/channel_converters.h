// A channel's converters: the D/A that carries the command to the rig and the A/D converters
// behind its displacement sensor and load cell (signal_converter.h), each off unless stated.
// Any plant can have them (servo.converters); a servo loop (feedback_controlled_plant.h) has
// them inside the loop, where its controller reads and writes through them.
#pragma once

#include "rpsd/config/source.h"
#include "rpsd/servo/signal_converter.h"

namespace rpsd::servo {

struct ChannelConverters {
  SignalConverterParameters command;       // D/A, m
  SignalConverterParameters displacement;  // displacement sensor and A/D, m
  SignalConverterParameters force;         // load cell and A/D, N

  bool any() const;
  // Each converter's own check, its name in the message ("converters.force: ...").
  void validate() const;
};

// The optional `converters` section of a plant: `seed` and `command`, `displacement`, `force`,
// each converter with its own noise stream (seed, seed + 1, seed + 2). Checked by validate().
ChannelConverters read_channel_converters(config::Source& plant_section);

}  // namespace rpsd::servo
