#include "rpsd/hybrid_test/in_process_site.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/servo/coupled_specimen_actuator.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/setups/setup_kinds.h"

namespace rpsd::hybrid_test {

namespace {

// The site's setup when it carries a coupled specimen to simulate, else nullptr.
const ExperimentalSetupSite* coupled_setup(const TestConfig& test, const SiteSetup& setup) {
  for (const ExperimentalSetupSite& s : test.setups) {
    if (s.site_id == setup.site_id && s.specimen_stiffness.size() > 0) return &s;
  }
  return nullptr;
}

// The geometry with its actuators in the site's channel order (the setup's actuator i is on
// the test channel setup.channels[i]; the node's channel j is the site's channels[j]).
setups::PlanarGeometry in_site_order(const ExperimentalSetupSite& coupled, const SiteSetup& setup) {
  const setups::PlanarGeometry given = setups::planar_geometry(coupled.setup);
  setups::PlanarGeometry ordered = given;
  if (coupled.channels.size() != setup.channels.size() ||
      static_cast<int>(coupled.channels.size()) != given.dof_count) {
    throw std::invalid_argument("site " + std::to_string(setup.site_id) + ": its setup drives " +
                                std::to_string(given.dof_count) + " DOFs on " +
                                std::to_string(coupled.channels.size()) + " channels, the site has " +
                                std::to_string(setup.channels.size()));
  }
  for (std::size_t j = 0; j < setup.channels.size(); ++j) {
    std::size_t i = 0;
    while (i < coupled.channels.size() && coupled.channels[i] != setup.channels[j]) ++i;
    if (i == coupled.channels.size()) {
      throw std::invalid_argument("site " + std::to_string(setup.site_id) + ": its channel " +
                                  std::to_string(setup.channels[j]) + " is none of its setup's actuators");
    }
    ordered.actuators[j] = given.actuators[i];
  }
  return ordered;
}

}  // namespace

std::unique_ptr<Site> InProcessSite::make(const TestConfig& test, const SiteSetup& setup, SiteResources& /*shared*/) {
  return std::unique_ptr<Site>(new InProcessSite(test, setup));
}

InProcessSite::InProcessSite(const TestConfig& test, const SiteSetup& setup) {
  if (const ExperimentalSetupSite* coupled = coupled_setup(test, setup)) {
    if (!setup.held_force.empty()) {
      throw std::invalid_argument("site " + std::to_string(setup.site_id) +
                                  ": a held force beside a coupled specimen is not simulated in this process");
    }
    // One specimen couples the actuators: each its own plant without a specimen of its own.
    servo::PlantConfig plant;
    try {
      plant = setup.perfect_actuator ? servo::perfect_coupled_plant_config() : servo::coupled_plant_config(test.plant);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("site " + std::to_string(setup.site_id) + ": " + e.what());
    }
    actuator_.plants = servo::make_plants(plant, static_cast<int>(setup.channels.size()));
    actuator_.actuator = std::make_unique<servo::CoupledSpecimenActuator>(
        actuator_.plants.pointers, setups::PlanarSetup(in_site_order(*coupled, setup)), coupled->specimen_stiffness,
        coupled->specimen_damping);
  } else {
    // Each channel its own plant: the test's, or one that follows its command exactly; a held
    // force's pushes on its own specimen.
    for (std::size_t i = 0; i < setup.stiffness_estimate_n_per_m.size(); ++i) {
      const double k = setup.stiffness_estimate_n_per_m[i];
      if (const int held = setup.held_force_of(i); held >= 0) {
        // What a node refuses, so is a held force here: a plant without a force loop.
        if (const std::string why = held_force_refusal(test.plant); !why.empty()) {
          throw std::invalid_argument(held_force_label(test.held_forces[static_cast<std::size_t>(held)]) +
                                      " cannot be simulated in this process: " + why);
        }
      }
      actuator_.plants.owned.push_back(servo::make_plant(
          setup.perfect_actuator        ? servo::PlantConfig{servo::PureDelayParameters{0.0, k, 8192.0, {}, {}}}
          : setup.held_force_of(i) >= 0 ? held_force_plant(test.plant, k)
                                        : test.plant));
      actuator_.plants.pointers.push_back(actuator_.plants.owned.back().get());
    }
    actuator_.actuator = std::make_unique<servo::SimulatedActuator>(actuator_.plants.pointers);
  }
  controller_ = std::make_unique<node::ServoNodeController>(setup.node.node, *actuator_.actuator);
  controller_->start(setup.hold_m);
  node_ = std::make_unique<node::LockStepNode>(*controller_);
  // Under a coupled specimen: each actuator's load at rest.
  for (const servo::Plant* plant : actuator_.plants.pointers) initial_force_n_.push_back(plant->measure().force_n);
  link_ = std::make_unique<transport::InProcessLink>(*node_);
}

std::string InProcessSite::node_fault_text() { return std::string(controller_->fault_text().data()); }

}  // namespace rpsd::hybrid_test
