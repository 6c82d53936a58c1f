// Simulated actuators loaded by one specimen whose restoring forces couple the DOFs of an
// experimental setup (rehearsal shows the actuators pushing against each other): each
// actuator is its own plant, and each control period
//   measured strokes s -> DOF displacements u (the setup's inverse, Newton from the last u)
//   and velocities (u - u_last) / T -> F = K u + C du/dt -> actuator loads J(u)^-T F,
// each load held on its plant over the next period (set_external_load_n). The plants' own
// specimens carry no stiffness or damping (coupled_plant_config), so nothing is counted twice.
// The explicit hold and its stability condition: docs/coupled-specimens.md.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string_view>

#include "rpsd/servo/actuator.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/setups/planar_setup.h"

namespace rpsd::servo {

// The plant configuration of one actuator under a coupled specimen: `config` with its own
// specimen's stiffness and damping zeroed (the coupled K and C carry them), its moving mass and
// friction kept (they are the actuator's and the piston's). std::invalid_argument for a kind
// that cannot carry a load from outside (feedback_controlled). Not real-time safe.
PlantConfig coupled_plant_config(const PlantConfig& config);

// Plants that follow their command exactly (an ideal delay of 0) with no specimen of their own:
// the perfect-actuator reference's under a coupled specimen. Not real-time safe.
PlantConfig perfect_coupled_plant_config();

class CoupledSpecimenActuator final : public Actuator {
 public:
  // `plants` (not owned, outliving the actuator): one per actuator of the setup, in its order,
  // each accepting an external load. `stiffness` and `damping` are square over the setup's
  // DOFs (N/m, N/rad, N m/rad, ... in the setup's DOF order); an empty damping is none.
  // std::invalid_argument naming what does not fit. Not real-time safe.
  CoupledSpecimenActuator(std::span<Plant* const> plants, setups::PlanarSetup setup, const Eigen::MatrixXd& stiffness,
                          const Eigen::MatrixXd& damping);

  int channels() const override { return simulated_.channels(); }

  // `initial_displacement_m` is each actuator's stroke at rest: the specimen's configuration is
  // solved from them and each plant is put at rest carrying its load there (at rest: no
  // velocity). std::invalid_argument when the geometry cannot solve them. Not real-time safe.
  void start(std::span<const double> initial_displacement_m) override;

  // Advances every plant over the period under the loads held from the last period, then
  // loads them for the next; the reading's forces are the load cells' after the new loads.
  // kFault, latched until start(), when the setup's geometry fails at the measured strokes
  // (fault_text() says how) or the forces are not finite. Real-time safe.
  ActuatorStatus exchange(std::span<const double> command_m, double period_s, ActuatorReading& reading) override;
  std::string_view fault_text() const noexcept override { return fault_text_; }

  // The specimen's DOF displacements and the actuators' loads after the last exchange or
  // start. Real-time safe.
  const setups::SetupVector& dof_displacements() const noexcept { return u_; }
  const setups::SetupVector& actuator_loads_n() const noexcept { return loads_n_; }

 private:
  // The DOFs from the measured strokes, the specimen's forces and each plant's load; false
  // (fault_text_ set) on failure. Real-time safe.
  bool load_plants(const ActuatorReading& reading, double period_s);

  SimulatedActuator simulated_;
  std::array<Plant*, kMaxChannels> plants_{};
  setups::PlanarSetup setup_;
  setups::SetupMatrix K_, C_;
  setups::SetupVector strokes_m_, u_, u_last_, velocity_, dof_forces_, loads_n_;
  bool faulted_ = false;
  std::string_view fault_text_;
};

}  // namespace rpsd::servo
