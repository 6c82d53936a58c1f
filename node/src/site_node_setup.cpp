#include "rpsd/node/site_node_setup.h"

#include <algorithm>

namespace rpsd::node {

void SiteNodeSetup::complete() {
  limit_to_envelope(node, rig);
  if (converters) {
    if (converters_key.empty()) {
      read_through_converters(node, *converters);
    } else {
      limit_to_converters(node, *converters, converters_key);
    }
  }
  // The force guard predicts the force a command will bring: the stiffest specimen known
  // makes it act soonest.
  for (int c = 0; c < node.channels; ++c) {
    double& k = node.limits[static_cast<std::size_t>(c)].force_guard_stiffness_n_per_m;
    if (k == 0.0) k = specimen_stiffness_n_per_m[static_cast<std::size_t>(c)];
  }
}

double stiffest_specimen_n_per_m(const servo::PlantConfig& plant, double estimate_n_per_m) {
  return std::max(servo::specimen_stiffness_of(plant), estimate_n_per_m);
}

}  // namespace rpsd::node
