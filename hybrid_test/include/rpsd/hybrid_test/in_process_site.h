// A site whose servo node runs in this process as `rpsd servo-node` would run it (its limits,
// actions and watchdog), on simulated plants, answered in lock-step: deterministic, and the
// perfect-actuator reference's way to every actuator site. A site whose setup carries a
// coupled specimen (ExperimentalSetupSite::specimen_stiffness) simulates its actuators under
// that one specimen (servo/coupled_specimen_actuator.h): channel j's plant is the setup's
// actuator on the site's channel j, and setup.hold_m are the actuators' strokes at rest.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/hybrid_test/site.h"
#include "rpsd/hybrid_test/site_setup.h"
#include "rpsd/node/lock_step_node.h"
#include "rpsd/node/owned_actuator.h"
#include "rpsd/node/servo_node_controller.h"
#include "rpsd/transport/in_process_link.h"

namespace rpsd::hybrid_test {

class InProcessSite final : public Site {
 public:
  static constexpr std::string_view kName = "in_process";
  static constexpr std::string_view kSummary = "a simulated servo node in this process, in lock-step";
  // Any actuator site the other kinds leave: the last in the list.
  static bool serves(const TestConfig& /*test*/, const SiteSetup& /*setup*/) { return true; }
  // Not real-time safe.
  static std::unique_ptr<Site> make(const TestConfig& test, const SiteSetup& setup, SiteResources& shared);

  transport::Link& link() override { return *link_; }
  // The simulated load cell's, once the node holds the actuators at rest (under a coupled
  // specimen: each actuator's load there).
  double initial_force_n(std::size_t i) const override { return initial_force_n_[i]; }
  bool initial_force_measured(std::size_t /*i*/) const override { return true; }
  const servo::Plant* simulated_plant(std::size_t i) const override { return actuator_.plants.pointers[i]; }
  // What faulted the node, as it keeps it (a simulated coupled specimen's failed geometry).
  std::string node_fault_text() override;

 private:
  InProcessSite(const TestConfig& test, const SiteSetup& setup);

  node::OwnedActuator actuator_;
  std::unique_ptr<node::ServoNodeController> controller_;
  std::unique_ptr<node::LockStepNode> node_;
  std::unique_ptr<transport::InProcessLink> link_;
  std::vector<double> initial_force_n_;
};

}  // namespace rpsd::hybrid_test
