// The simulated plants rpsd knows, registered in one place (the list below): a new plant is
// its own files (its parameters naming themselves with kName, reading their keys with read(),
// and naming the Plant they build) plus one entry here (CONTRIBUTING.md). Not real-time safe.
#pragma once

#include <memory>
#include <vector>

#include "rpsd/config/kind_list.h"
#include "rpsd/servo/feedback_controlled_plant.h"
#include "rpsd/servo/plant.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_parameters.h"
#include "rpsd/servo/transfer_function_plant.h"

namespace rpsd::servo {

// The actuator of a channel: the seed paper's servo-hydraulic model, an ideal delay, a
// transfer function from command to displacement, or a PID loop around a plant from the
// controller's output.
using PlantKinds = config::KindList<ServoSystemParameters, PureDelayParameters, TransferFunctionPlantParameters,
                                    FeedbackControlledPlantParameters>;
using PlantConfig = PlantKinds::Variant;

std::unique_ptr<Plant> make_plant(const PlantConfig& config);

// A plant section: its `kind` and that kind's keys. The specimen stiffness is the load cell's
// k for the plants that have no specimen of their own. Not real-time safe.
PlantConfig read_plant_config(config::Source& section, double specimen_stiffness_n_per_m);

// Checks what depends on the control period (a servo loop's controller): std::invalid_argument
// naming the problem. Not real-time safe.
void check_control_period(const PlantConfig& config, double control_period_s);

// The rig the configuration describes (infinite when none was stated: a numerical reference).
Envelope envelope_of(const PlantConfig& config);
// What the configuration's A/D converters can read on each channel (every channel has the same):
// the displacement's range in m and the force's in N, infinite without converters. A reading at
// a rail faults a node; a limit must lie strictly inside (require_readable).
ReadingRanges reading_ranges_of(const PlantConfig& config);
// The stiffness of the specimen the configuration's load cell sees (its initial stiffness).
double specimen_stiffness_of(const PlantConfig& config);

// One plant per channel, all of one configuration, with the pointers an actuator borrows.
struct PlantSet {
  std::vector<std::unique_ptr<Plant>> owned;
  std::vector<Plant*> pointers;
};
PlantSet make_plants(const PlantConfig& config, int channels);

}  // namespace rpsd::servo
