#pragma once
// Linear multi-DOF model: R(d) = K d with M, C, K given as dense or sparse matrices
// (small models written in a scenario, or large ones read from Matrix Market files).

#include "rpsd/substructure/damping.h"
#include "rpsd/substructure/numerical_model.h"

#include <optional>
#include <string>

namespace rpsd::substructure {

struct LinearMdofParameters {
  linalg::StructuralMatrix mass_kg;            // symmetric positive definite
  linalg::StructuralMatrix stiffness_n_per_m;  // symmetric, no negative diagonal entry
  DampingConfig damping = Undamped{};
  // Where each matrix came from (e.g. "file 'k.mtx'"); added to error messages when set.
  std::string mass_source;
  std::string stiffness_source;
  std::string damping_source;
};
using LinearMdofConfig [[deprecated("renamed LinearMdofParameters (docs/migration.md)")]] = LinearMdofParameters;

class LinearMdofModel final : public NumericalModel {
 public:
  // Validates sizes, finiteness, symmetry of M and K, positive definiteness of M, the sign
  // of K's diagonal, and builds C. Throws std::invalid_argument. Not real-time safe.
  void configure(const LinearMdofParameters& config);

  [[nodiscard]] Eigen::Index dofs() const noexcept override { return K_.rows(); }
  [[nodiscard]] const linalg::StructuralMatrix& mass() const noexcept override { return M_; }
  [[nodiscard]] const linalg::StructuralMatrix& damping() const noexcept override { return C_; }
  [[nodiscard]] const linalg::StructuralMatrix& initial_stiffness() const noexcept override { return K_; }
  // A linear model's tangent is K. Real-time safe.
  [[nodiscard]] const linalg::StructuralMatrix& tangent_stiffness() noexcept override { return K_; }

  // r_out = K d_trial. Real-time safe.
  void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial,
                       Eigen::Ref<Eigen::VectorXd> r_out) noexcept override;
  // No history to commit. Real-time safe.
  void commit() noexcept override {}

  // The Rayleigh coefficients used, if the damping was Rayleigh.
  [[nodiscard]] const std::optional<RayleighCoefficients>& rayleigh() const noexcept { return rayleigh_; }

 private:
  linalg::StructuralMatrix M_, C_, K_;
  std::optional<RayleighCoefficients> rayleigh_;
};

}  // namespace rpsd::substructure
