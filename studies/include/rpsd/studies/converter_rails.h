// A channel's converter rails as the pre-test checks show them: the largest magnitude each of
// its converters can represent on both sides, in the units of the signal it carries (m, N),
// from servo's own ranges (SignalConverterParameters::range). Not real-time safe.
#pragma once

#include "rpsd/servo/envelope.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/servo/signal_converter.h"

namespace rpsd::studies {

// The largest |value| the converter represents on both sides (the nearer rail); infinite
// without a voltage stage or without a limit.
double converter_rail(const servo::SignalConverterParameters& converter);

struct ConverterRails {
  // The D/A that carries the coordinator's command (infinite when the plant's D/A carries a
  // servo controller's output instead: feedback_controlled_plant.h).
  double command_m = servo::Envelope::kNone;
  double displacement_m = servo::Envelope::kNone;  // the displacement sensor's A/D
  double force_n = servo::Envelope::kNone;         // the load cell's A/D
};

ConverterRails converter_rails(const servo::PlantConfig& plant);

}  // namespace rpsd::studies
