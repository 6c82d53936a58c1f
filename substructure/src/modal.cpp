#include "rpsd/substructure/modal.h"

#include "matrix_checks.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::substructure {
namespace {

Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solve(const linalg::StructuralMatrix& M,
                                                                const linalg::StructuralMatrix& K, bool vectors) {
  const std::string ctx = "modal analysis: ";
  detail::require_square(M, ctx + "mass matrix M");
  detail::require_size(K, M.rows(), ctx + "stiffness matrix K");
  if (M.rows() > kMaxDenseEigenDofs) {
    throw std::invalid_argument(
        ctx + "the model has " + std::to_string(M.rows()) + " DOFs, more than the dense eigen-solver limit of " +
        std::to_string(kMaxDenseEigenDofs) + "; give the two frequencies directly (RayleighFromFrequencies)");
  }
  detail::require_finite(M, ctx + "mass matrix M");
  detail::require_finite(K, ctx + "stiffness matrix K");
  detail::require_symmetric(M, ctx + "mass matrix M");
  detail::require_symmetric(K, ctx + "stiffness matrix K");
  detail::require_positive_definite(M, ctx + "mass matrix M");

  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
      K.to_dense(), M.to_dense(), (vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly) | Eigen::Ax_lBx);
  if (es.info() != Eigen::Success) {
    throw std::invalid_argument(ctx + "the eigen-solver did not converge");
  }
  // ω² slightly below zero is round-off on a singular K (a rigid-body mode): clamp it.
  const Eigen::VectorXd& lambda = es.eigenvalues();
  const double scale = lambda.cwiseAbs().maxCoeff();
  if (lambda[0] < -1e-10 * scale) {
    throw std::invalid_argument(ctx +
                                "stiffness matrix K is not positive semi-definite: mode 1 has "
                                "omega^2 = " +
                                detail::fmt(lambda[0]) + " (rad/s)^2");
  }
  return es;
}

}  // namespace

ModalSolution modal_analysis(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness) {
  auto es = solve(mass, stiffness, true);
  ModalSolution out;
  out.omega_rad_s = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  out.modes = es.eigenvectors();  // Eigen normalises them so that φᵀ M φ = 1
  return out;
}

Eigen::VectorXd natural_frequencies_rad_s(const linalg::StructuralMatrix& mass,
                                          const linalg::StructuralMatrix& stiffness) {
  auto es = solve(mass, stiffness, false);
  return es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace rpsd::substructure
