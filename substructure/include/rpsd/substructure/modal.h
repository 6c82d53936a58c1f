#pragma once
// Natural frequencies and mode shapes from the generalized eigenproblem K φ = ω² M φ.

#include "rpsd/linalg/structural_matrix.h"

#include <Eigen/Core>

namespace rpsd::substructure {

// The eigenproblem is solved densely (Eigen::GeneralizedSelfAdjointEigenSolver, O(n³)).
// Sparse matrices are converted to dense up to this many DOFs (2000 DOFs: 32 MB per matrix
// and a few seconds of solve); a larger model's lowest modes come from the sparse solver
// (lowest_modes_sparse: validate, the dry run, Rayleigh damping through two modes), and modal
// damping of every mode stays limited to this size.
inline constexpr Eigen::Index kMaxDenseEigenDofs = 2000;

struct ModalSolution {
  Eigen::VectorXd omega_rad_s;  // ascending natural circular frequencies
  Eigen::MatrixXd modes;        // column k is mode k, mass-normalised: φᵀ M φ = 1
};

// Throws std::invalid_argument when M and K differ in size, are not square, symmetric or
// finite, when M is not positive definite, when K has a negative eigenvalue (beyond
// round-off), or when the model exceeds kMaxDenseEigenDofs. Not real-time safe.
[[nodiscard]] ModalSolution modal_analysis(const linalg::StructuralMatrix& mass,
                                           const linalg::StructuralMatrix& stiffness);

// The lowest `count` modes (fewer when the model has fewer DOFs), mass-normalised, ascending:
// by the dense solver up to kMaxDenseEigenDofs, above it by lowest_modes_sparse. Same checks,
// without the DOF limit. Not real-time safe.
[[nodiscard]] ModalSolution lowest_modes(const linalg::StructuralMatrix& mass,
                                         const linalg::StructuralMatrix& stiffness, Eigen::Index count);

// The lowest `count` (< DOFs) modes by a sparse eigen-solver (Spectra's shift-invert Lanczos
// about 0, K - sigma M factorised by a sparse LDLT): memory grows with the matrices' non-zeros,
// not with the DOFs squared, so a 100,000-DOF Matrix Market model is solved in megabytes.
// Throws std::invalid_argument as modal_analysis does, and when the solver does not converge.
// Not real-time safe.
[[nodiscard]] ModalSolution lowest_modes_sparse(const linalg::StructuralMatrix& mass,
                                                const linalg::StructuralMatrix& stiffness, Eigen::Index count);

// Only the frequencies (cheaper: no eigenvectors). Same checks. Not real-time safe.
[[nodiscard]] Eigen::VectorXd natural_frequencies_rad_s(const linalg::StructuralMatrix& mass,
                                                        const linalg::StructuralMatrix& stiffness);

}  // namespace rpsd::substructure
