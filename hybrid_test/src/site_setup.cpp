#include "rpsd/hybrid_test/site_setup.h"

#include "rpsd/hybrid_test/held_forces.h"

namespace rpsd::hybrid_test {

void SiteSetup::complete(const TestConfig& test) {
  node = {};
  if (!perfect_actuator) {
    if (const auto found = test.site_nodes.find(site_id); found != test.site_nodes.end()) {
      node.node = found->second;  // its limits, limit actions and watchdog
    }
  }
  node.node.test_id = test.transport.test_id;
  node.node.site_id = site_id;
  node.node.channels = static_cast<int>(channels.size());
  node.node.control_period_s = control_period_s;
  // A held force's channel: force control, its command within the held force's own limits.
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const int k = held_force_of(i);
    if (k < 0) continue;
    const HeldForce& held = test.held_forces[static_cast<std::size_t>(k)];
    node.node.control[i] = servo::ControlMode::kForce;
    node.node.limits[i].max_force_command_n = held_force_limits(held, servo::envelope_of(test.plant)).max_force_n;
    node.node.limits[i].max_force_rate_n_per_s = held.max_force_rate_n_per_s;
  }
  if (perfect_actuator) return;  // a perfect actuator follows its command: no rig to keep it in
  node.rig = servo::envelope_of(test.plant);
  // A reading at or beyond the rig's envelope, or on a converter's rail, faults the node (the
  // coordinator's limits were held inside the rails when the file was read: no key to check).
  node.converters = servo::reading_ranges_of(test.plant);
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const int k = held_force_of(i);
    node.specimen_stiffness_n_per_m[i] = node::stiffest_specimen_n_per_m(
        k < 0 ? test.plant
              : held_force_plant(test.plant, test.held_forces[static_cast<std::size_t>(k)].specimen_stiffness_n_per_m),
        stiffness_estimate_n_per_m[i]);
  }
  node.complete();
}

std::vector<double> estimated_initial_forces_n(const SiteSetup& setup) {
  std::vector<double> forces(setup.channels.size());
  for (std::size_t i = 0; i < forces.size(); ++i) forces[i] = setup.stiffness_estimate_n_per_m[i] * setup.hold_m[i];
  return forces;
}

}  // namespace rpsd::hybrid_test
