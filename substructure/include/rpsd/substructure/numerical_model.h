#pragma once
// The numerical substructure as the coordinator and the integrators see it: mass M, damping
// C, initial stiffness K0, and a restoring-force law R(d) evaluated with trial/commit
// semantics so that implicit schemes can iterate within a step.
//
// Two phases: the concrete model's configure() sizes and validates everything (not
// real-time safe, throws std::invalid_argument with a precise message); the methods below
// never allocate or throw.
//
// Trial/commit: restoring_force(d) always starts from the last committed state, so any
// number of trial evaluations within a step leave the history untouched; commit() accepts
// the last trial as the converged state of the step.

#include "rpsd/linalg/structural_matrix.h"

#include <Eigen/Core>

namespace rpsd::substructure {

class NumericalModel {
 public:
  virtual ~NumericalModel() = default;

  [[nodiscard]] virtual Eigen::Index dofs() const noexcept = 0;
  // M and C are one object each for the model's life (the loop holds them); their values
  // may change only when the model is configured again.
  [[nodiscard]] virtual const linalg::StructuralMatrix& mass() const noexcept = 0;
  [[nodiscard]] virtual const linalg::StructuralMatrix& damping() const noexcept = 0;
  [[nodiscard]] virtual const linalg::StructuralMatrix& initial_stiffness() const noexcept = 0;

  // Tangent stiffness at the last trial state (K0 before the first trial). Updated in
  // place, same storage and sparsity pattern as K0. Real-time safe.
  [[nodiscard]] virtual const linalg::StructuralMatrix& tangent_stiffness() noexcept = 0;

  // r_out = R(d_trial) from the committed state; both of size dofs(). Real-time safe.
  virtual void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial,
                               Eigen::Ref<Eigen::VectorXd> r_out) noexcept = 0;

  // Accepts the last trial as the committed state. Real-time safe.
  virtual void commit() noexcept = 0;

 protected:
  NumericalModel() = default;
  NumericalModel(const NumericalModel&) = default;
  NumericalModel& operator=(const NumericalModel&) = default;
  NumericalModel(NumericalModel&&) = default;
  NumericalModel& operator=(NumericalModel&&) = default;
};

}  // namespace rpsd::substructure
