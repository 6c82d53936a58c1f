// A servo node's configuration as given, with what its rig is, and the one place where the
// rig's defaults are applied to it (complete()): for a node file's `rpsd servo-node` and for a
// test's node in this process alike, so that both take one rule.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "rpsd/node/servo_node_config.h"
#include "rpsd/servo/envelope.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/transport/messages.h"

namespace rpsd::node {

struct SiteNodeSetup {
  ServoNodeConfig node;  // identity, period, and the limits, actions and watchdog as given
  servo::Envelope rig;   // what the actuators can do
  // What the readings come through (simulated plants); unknown for a hardware controller.
  std::optional<servo::ReadingRanges> converters;
  // Non-empty: the node's limits are the only ones (a node file), so each stated or rig
  // limit must lie strictly inside what the converters can read; named in errors
  // ("actuator.servo.converters"). Empty: a coordinator's limits were held inside them.
  std::string converters_key;
  // Per channel, the stiffest specimen known (the simulated specimen's, the test's
  // estimate): what the force guard predicts with when the node states none. 0: none known.
  std::array<double, transport::kMaxChannels> specimen_stiffness_n_per_m{};

  // The rig's envelope becomes every limit's default and ceiling, the readings go through
  // the converters, and a force guard left at 0 takes specimen_stiffness_n_per_m. Throws
  // config::KeyError at limits[c].key for a limit beyond the rig or not readable. Not
  // real-time safe.
  void complete();
};

// The stiffest of a simulated plant's specimen and an estimate: the force guard's default.
double stiffest_specimen_n_per_m(const servo::PlantConfig& plant, double estimate_n_per_m);

}  // namespace rpsd::node
