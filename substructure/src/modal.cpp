#include "rpsd/substructure/modal.h"

#include "matrix_checks.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <numeric>
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

void check_matrices(const linalg::StructuralMatrix& M, const linalg::StructuralMatrix& K, const std::string& ctx) {
  detail::require_square(M, ctx + "mass matrix M");
  detail::require_size(K, M.rows(), ctx + "stiffness matrix K");
  detail::require_finite(M, ctx + "mass matrix M");
  detail::require_finite(K, ctx + "stiffness matrix K");
  detail::require_symmetric(M, ctx + "mass matrix M");
  detail::require_symmetric(K, ctx + "stiffness matrix K");
  detail::require_positive_definite(M, ctx + "mass matrix M");
}

// (K - sigma M)^-1 x for Spectra's shift-invert mode, by a sparse LDLT (K and M symmetric).
// Its D counts the eigenvalues below sigma (Sylvester's law of inertia).
class ShiftInvertLdlt {
 public:
  using Scalar = double;
  ShiftInvertLdlt(const linalg::SparseMatrix& K, const linalg::SparseMatrix& M) : K_(K), M_(M) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    ldlt_.compute(linalg::SparseMatrix(K_ - sigma * M_));
    if (ldlt_.info() != Eigen::Success) throw std::invalid_argument("K - sigma M could not be factorised");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = ldlt_.solve(x);
  }
  // Pivots of the factorisation below zero, and the largest pivot's size.
  Eigen::Index negative_pivots() const { return (ldlt_.vectorD().array() < 0.0).count(); }
  double largest_pivot() const { return ldlt_.vectorD().cwiseAbs().maxCoeff(); }
  double smallest_pivot() const { return ldlt_.vectorD().cwiseAbs().minCoeff(); }

 private:
  const linalg::SparseMatrix& K_;
  const linalg::SparseMatrix& M_;
  Eigen::SimplicialLDLT<linalg::SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
};

}  // namespace

ModalSolution lowest_modes_sparse(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness,
                                  Eigen::Index count) {
  const std::string ctx = "modal analysis: ";
  check_matrices(mass, stiffness, ctx);
  const Eigen::Index n = mass.rows();
  if (count < 1 || count >= n) {
    throw std::invalid_argument(ctx + "the sparse eigen-solver finds 1 to " + std::to_string(n - 1) +
                                " of the lowest modes, not " + std::to_string(count));
  }
  const linalg::SparseMatrix K = stiffness.to_sparse(), M = mass.to_sparse();
  ShiftInvertLdlt op(K, M);
  // The shift 0 finds the lowest modes fastest; a K with rigid-body modes (singular) is shifted
  // just below zero instead, by 1e-10 of its largest k_ii / m_ii.
  double sigma = 0.0;
  bool factorised = false;
  try {
    op.set_shift(0.0);
    factorised = op.smallest_pivot() > 1e-13 * op.largest_pivot();
  } catch (const std::invalid_argument&) {
  }
  if (!factorised) {
    double scale = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) scale = std::max(scale, stiffness.coeff(i, i) / mass.coeff(i, i));
    sigma = -1e-10 * std::max(scale, 1.0);
    try {
      op.set_shift(sigma);
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument(
          ctx + "stiffness matrix K - sigma M could not be factorised (sigma = " + detail::fmt(sigma) + ")");
    }
  }
  if (op.negative_pivots() > 0) {
    throw std::invalid_argument(
        ctx + "stiffness matrix K is not positive semi-definite: " + std::to_string(op.negative_pivots()) +
        " mode(s) with omega^2 below " + detail::fmt(sigma) + " (rad/s)^2");
  }
  Spectra::SparseSymMatProd<double> mass_product(M);
  const Eigen::Index subspace = std::min(n, std::max<Eigen::Index>(2 * count + 1, 20));
  Spectra::SymGEigsShiftSolver<ShiftInvertLdlt, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      solver(op, mass_product, count, subspace, sigma);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  if (solver.info() != Spectra::CompInfo::Successful) {
    throw std::invalid_argument(ctx + "the sparse eigen-solver did not converge on the lowest " +
                                std::to_string(count) + " modes");
  }
  const Eigen::VectorXd lambda = solver.eigenvalues();
  const Eigen::MatrixXd vectors = solver.eigenvectors();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(lambda.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return lambda[a] < lambda[b]; });
  ModalSolution out;
  out.omega_rad_s.resize(lambda.size());
  out.modes.resize(n, lambda.size());
  Eigen::VectorXd m_phi(n);
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    const Eigen::Index k = order[static_cast<std::size_t>(i)];
    out.omega_rad_s[i] = std::sqrt(std::max(lambda[k], 0.0));
    Eigen::VectorXd phi = vectors.col(k);
    mass.multiply(phi, m_phi);
    phi /= std::sqrt(phi.dot(m_phi));  // phi' M phi = 1, as the dense solver gives
    // The sign the dense solver would not fix either; make the largest entry positive.
    Eigen::Index largest = 0;
    phi.cwiseAbs().maxCoeff(&largest);
    if (phi[largest] < 0.0) phi = -phi;
    out.modes.col(i) = phi;
  }
  return out;
}

ModalSolution lowest_modes(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness,
                           Eigen::Index count) {
  if (mass.rows() > kMaxDenseEigenDofs && count < mass.rows()) return lowest_modes_sparse(mass, stiffness, count);
  ModalSolution all = modal_analysis(mass, stiffness);
  const Eigen::Index kept = std::min(count, all.omega_rad_s.size());
  return {all.omega_rad_s.head(kept), all.modes.leftCols(kept)};
}

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
