#include "rpsd/hybrid_test/in_process_site.h"

#include <utility>

#include "rpsd/servo/simulated_actuator.h"

namespace rpsd::hybrid_test {

std::unique_ptr<Site> InProcessSite::make(const TestConfig& test, const SiteSetup& setup, SiteResources& /*shared*/) {
  return std::unique_ptr<Site>(new InProcessSite(test, setup));
}

InProcessSite::InProcessSite(const TestConfig& test, const SiteSetup& setup) {
  // Each channel its own plant: the test's, or one that follows its command exactly.
  for (const double k : setup.stiffness_estimate_n_per_m) {
    actuator_.plants.owned.push_back(servo::make_plant(
        setup.perfect_actuator ? servo::PlantConfig{servo::PureDelayParameters{0.0, k, 8192.0, {}, {}}} : test.plant));
    actuator_.plants.pointers.push_back(actuator_.plants.owned.back().get());
  }
  actuator_.actuator = std::make_unique<servo::SimulatedActuator>(actuator_.plants.pointers);
  controller_ = std::make_unique<node::ServoNodeController>(setup.node.node, *actuator_.actuator);
  controller_->start(setup.hold_m);
  node_ = std::make_unique<node::LockStepNode>(*controller_);
  for (const servo::Plant* plant : actuator_.plants.pointers) initial_force_n_.push_back(plant->measure().force_n);
  link_ = std::make_unique<transport::InProcessLink>(*node_);
}

}  // namespace rpsd::hybrid_test
