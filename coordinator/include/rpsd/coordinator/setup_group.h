// The channels an experimental setup drives, as the exchange with the sites sees them: the
// setup's DOF i and its actuator i share the test's channel channels[i], the loop's targets
// and restoring forces on those channels are the DOFs', the link's commands and feedback the
// actuators'. Configured once (ExchangeParts::setups); the exchange turns one into the other
// on the real-time path (experimental_exchange.h).
#pragma once

#include <cstdint>
#include <vector>

#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/setups/planar_setup.h"

namespace rpsd::coordinator {

struct SetupGroup {
  std::uint32_t site_id = 1;  // for names in messages
  setups::PlanarGeometry geometry;
  // The test's channel of each DOF i (and of actuator i), in the setup's order.
  std::vector<int> channels;
  // Where the channels' compensators act: on the DOFs' targets before the geometry, or on
  // the actuators' strokes after it.
  bool compensate_dofs = false;
  // Each actuator's limits, on its stroke as sent (offset included), its increment, its
  // load-cell force and its tracking error (empty: none). The DOFs' limits are the channels'
  // own (ExchangeParts::limits): on the DOFs' targets, forces and tracking errors.
  std::vector<CoordinatorLimits> actuator_limits;
  // Each actuator's reading at the initial configuration less the stroke the geometry
  // predicts there (calibration): added to every command, taken off every measurement
  // (empty: none).
  std::vector<double> calibration_offset_m;
};

}  // namespace rpsd::coordinator
