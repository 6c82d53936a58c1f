#include "rpsd/servo/coupled_specimen_actuator.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace rpsd::servo {

namespace {

constexpr std::string_view kSingularText =
    "the simulated coupled specimen: the setup's Jacobian is singular at the measured strokes";
constexpr std::string_view kNotConvergedText =
    "the simulated coupled specimen: the setup's geometry did not converge on the measured strokes";
constexpr std::string_view kMirroredText =
    "the simulated coupled specimen: the measured strokes solve to a configuration mirrored from the reference one";
constexpr std::string_view kNotFiniteText = "the simulated coupled specimen: its forces are not finite";

setups::SetupMatrix square_over_dofs(const Eigen::MatrixXd& m, int dofs, const char* what, bool empty_is_zero) {
  if (m.size() == 0 && empty_is_zero) return setups::SetupMatrix::Zero(dofs, dofs);
  if (m.rows() != dofs || m.cols() != dofs) {
    throw std::invalid_argument(std::string("the coupled specimen's ") + what + " is " + std::to_string(m.rows()) +
                                "x" + std::to_string(m.cols()) + ", the setup has " + std::to_string(dofs) + " DOFs");
  }
  if (!m.allFinite()) throw std::invalid_argument(std::string("the coupled specimen's ") + what + " is not finite");
  return m;
}

}  // namespace

PlantConfig coupled_plant_config(const PlantConfig& config) {
  PlantConfig coupled = config;
  std::visit(
      [](auto& p) {
        using Kind = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<Kind, ServoSystemParameters>) {
          p.specimen.stiffness = {};
          p.specimen.damping_ratio = 0.0;
        } else if constexpr (std::is_same_v<Kind, FeedbackControlledPlantParameters>) {
          throw std::invalid_argument(
              "a feedback_controlled plant cannot carry a coupled specimen: its load cell reads the specimen of its "
              "own transfer function behind the servo loop (use servo_model, ideal_delay or transfer_function)");
        } else if constexpr (std::is_same_v<Kind, TransferFunctionPlantParameters>) {
          p.specimen_stiffness_n_per_m = 0.0;
          p.specimen_damping_n_s_per_m = 0.0;
        } else {
          p.specimen_stiffness_n_per_m = 0.0;
        }
      },
      coupled);
  return coupled;
}

PlantConfig perfect_coupled_plant_config() { return PureDelayParameters{0.0, 0.0, 8192.0, {}, {}}; }

CoupledSpecimenActuator::CoupledSpecimenActuator(std::span<Plant* const> plants, setups::PlanarSetup setup,
                                                 const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& damping)
    : simulated_(plants), setup_(std::move(setup)) {
  const int n = setup_.actuators();
  if (static_cast<int>(plants.size()) != n) {
    throw std::invalid_argument("a coupled specimen on a setup of " + std::to_string(n) + " actuators needs " +
                                std::to_string(n) + " plants, one per actuator (" + std::to_string(plants.size()) +
                                " given)");
  }
  for (int i = 0; i < n; ++i) {
    if (!plants[static_cast<std::size_t>(i)]->accepts_external_load()) {
      throw std::invalid_argument("the plant of actuator " + std::to_string(i + 1) +
                                  " cannot carry a coupled specimen's load (a feedback-controlled plant's load cell "
                                  "reads its own specimen)");
    }
    plants_[static_cast<std::size_t>(i)] = plants[static_cast<std::size_t>(i)];
  }
  K_ = square_over_dofs(stiffness, n, "stiffness", false);
  C_ = square_over_dofs(damping, n, "damping", true);
  for (auto* v : {&strokes_m_, &u_, &u_last_, &velocity_, &dof_forces_, &loads_n_}) *v = setups::SetupVector::Zero(n);
}

void CoupledSpecimenActuator::start(std::span<const double> initial_displacement_m) {
  const int n = channels();
  if (static_cast<int>(initial_displacement_m.size()) != n) {
    throw std::invalid_argument("the coupled specimen's actuators: " + std::to_string(n) +
                                " strokes at rest expected, got " + std::to_string(initial_displacement_m.size()));
  }
  for (int i = 0; i < n; ++i) strokes_m_[i] = initial_displacement_m[static_cast<std::size_t>(i)];
  if (!strokes_m_.allFinite()) throw std::invalid_argument("the coupled specimen's strokes at rest are not finite");
  const setups::SetupStatus solved = setup_.displacements(strokes_m_, setups::SetupVector::Zero(n), u_);
  if (solved != setups::SetupStatus::kOk) {
    throw std::invalid_argument("the coupled specimen at rest: " + std::string(setups::setup_status_text(solved)));
  }
  // At rest: no velocity, so only the stiffness loads the plants.
  dof_forces_.noalias() = K_ * u_;
  const setups::SetupStatus carried = setup_.actuator_forces(u_, dof_forces_, loads_n_);
  if (carried != setups::SetupStatus::kOk || !loads_n_.allFinite()) {
    throw std::invalid_argument("the coupled specimen at rest: " + std::string(setups::setup_status_text(carried)));
  }
  for (int i = 0; i < n; ++i) plants_[static_cast<std::size_t>(i)]->set_external_load_n(loads_n_[i]);
  simulated_.start(initial_displacement_m);  // each plant at rest carrying its load
  u_last_ = u_;
  faulted_ = false;
  fault_text_ = {};
}

bool CoupledSpecimenActuator::load_plants(const ActuatorReading& reading, double period_s) {
  const int n = channels();
  for (int i = 0; i < n; ++i) strokes_m_[i] = reading.displacement_m[static_cast<std::size_t>(i)];
  const setups::SetupStatus solved = setup_.displacements(strokes_m_, u_last_, u_);
  if (solved != setups::SetupStatus::kOk) {
    fault_text_ = solved == setups::SetupStatus::kSingular   ? kSingularText
                  : solved == setups::SetupStatus::kMirrored ? kMirroredText
                                                             : kNotConvergedText;
    return false;
  }
  velocity_ = (u_ - u_last_) / period_s;
  dof_forces_.noalias() = K_ * u_;
  dof_forces_.noalias() += C_ * velocity_;
  if (setup_.actuator_forces(u_, dof_forces_, loads_n_) != setups::SetupStatus::kOk) {
    fault_text_ = kSingularText;
    return false;
  }
  if (!loads_n_.allFinite()) {
    fault_text_ = kNotFiniteText;
    return false;
  }
  for (int i = 0; i < n; ++i) plants_[static_cast<std::size_t>(i)]->set_external_load_n(loads_n_[i]);
  u_last_ = u_;
  return true;
}

ActuatorStatus CoupledSpecimenActuator::exchange(std::span<const double> command_m, double period_s,
                                                 ActuatorReading& reading) {
  if (faulted_) return ActuatorStatus::kFault;
  const ActuatorStatus status = simulated_.exchange(command_m, period_s, reading);
  if (status != ActuatorStatus::kOk) return status;
  if (!load_plants(reading, period_s)) {
    faulted_ = true;
    return ActuatorStatus::kFault;
  }
  // The load cells after the new loads (a plant whose load cell is its own state, the
  // servo-hydraulic model's chambers, reads the same until it moves).
  for (int i = 0; i < channels(); ++i) {
    reading.force_n[static_cast<std::size_t>(i)] = plants_[static_cast<std::size_t>(i)]->measure().force_n;
  }
  return ActuatorStatus::kOk;
}

}  // namespace rpsd::servo
