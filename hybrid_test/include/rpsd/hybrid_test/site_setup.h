// One site of a test as the site factory (site_kinds.h) takes it: which site, the test's
// channels it owns, what the run asks of it, and the servo node it runs when its node is in
// this process. complete() is where the rig's envelope and the force guard's default come in.
#pragma once

#include <cstdint>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/node/site_node_setup.h"

namespace rpsd::hybrid_test {

struct SiteSetup {
  std::uint32_t site_id = 1;
  std::vector<int> channels;                       // the test's channels, in channel order
  std::vector<double> hold_m;                      // per site channel: where its actuator rests
  std::vector<double> stiffness_estimate_n_per_m;  // per site channel: the specimen's estimate
  // Per site channel: the test's held force it holds in force control (TestConfig::held_forces
  // index), or -1: it follows displacements. Empty: none holds a force. Held channels come
  // after the site's structure channels.
  std::vector<int> held_force;
  double control_period_s = 0.0;
  std::uint64_t run_id = 0;
  // The perfect-actuator reference: plants that follow their command exactly, a node with no
  // limits, and an OpenSees site's reference process.
  bool perfect_actuator = false;
  // The node that answers for the site when it runs in this process (complete() sets it).
  node::SiteNodeSetup node;

  // The site's node as the test gives it (site_nodes, else the defaults) with the test's
  // identity and period; unless perfect_actuator, the rig's envelope as every limit's default
  // and ceiling, the readings through the plant's converters, and a force guard left at 0
  // predicting with the stiffest of the plant's specimen and the site's estimate. A held
  // force's channel is put in force control, its force command limited to the held force's
  // max_force_n and its rate to the held rate. A node in another process takes the same
  // defaults from its node file (node::SiteNodeSetup). Throws config::KeyError for a limit
  // beyond the rig. Not real-time safe.
  void complete(const TestConfig& test);
  // Held force index of site channel i, or -1.
  int held_force_of(std::size_t i) const { return i < held_force.size() ? held_force[i] : -1; }
};

// A remote site's forces at rest, before any feedback: its stiffness estimates times the hold.
std::vector<double> estimated_initial_forces_n(const SiteSetup& setup);

}  // namespace rpsd::hybrid_test
