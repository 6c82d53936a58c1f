#pragma once
// Factorises a symmetric linalg::StructuralMatrix once (configure time) and solves with it on the
// real-time path: diagonal inverse, dense LDLT, a band LDL^T for sparse matrices that are
// banded in their own numbering (frame models: contiguous, vectorised substitutions), or
// Eigen's sparse simplicial LDL^T with AMD ordering otherwise.
#include "rpsd/linalg/structural_matrix.h"

#include <Eigen/SparseCholesky>

#include <memory>
#include <string_view>

namespace rpsd::integrators {

class SymmetricSolver {
 public:
  SymmetricSolver();
  ~SymmetricSolver();
  SymmetricSolver(SymmetricSolver&&) noexcept;
  SymmetricSolver& operator=(SymmetricSolver&&) noexcept;

  // Not real-time safe. Throws std::invalid_argument naming `what` if A is singular.
  void factorize(const linalg::StructuralMatrix& A, std::string_view what);
  // x = A^-1 b. Real-time safe; x must already have the right size and not alias b.
  // Uses an internal work vector: one solver must not be used by two threads at once.
  // The diagonal arm is inline (below): a lumped mass's few products cost less than a call.
  // N, when given, is the size known when the caller is compiled (a scheme's one-DOF step).
  template <int N = Eigen::Dynamic>
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  linalg::MatrixStorage storage() const { return storage_; }
  // Non-zeros of the triangular factor (the per-solve cost); n for a diagonal matrix.
  Eigen::Index factor_nonzeros() const;

 private:
  using SparseLdlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
  linalg::MatrixStorage storage_ = linalg::MatrixStorage::kDiagonal;
  Eigen::VectorXd inverse_diagonal_;  // diagonal matrix, or D^-1 of the sparse AMD LDL^T
  std::unique_ptr<Eigen::LDLT<Eigen::MatrixXd>> dense_;
  std::unique_ptr<SparseLdlt> sparse_amd_;
  // Eigen's SimplicialLDLT::solve applies the fill-reducing permutation in place, which
  // allocates a mask; the AMD path permutes out of place through this vector instead.
  mutable Eigen::VectorXd work_;
  // Band LDL^T: row i of band_l_ holds L(i, i-b .. i-1); inverse_diagonal_ holds D^-1.
  Eigen::Index band_ = -1;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> band_l_;
  void factorize_band(const Eigen::SparseMatrix<double>& a, Eigen::Index b, std::string_view what);
  void solve_band(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  void solve_factored(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;  // dense and sparse
};

template <int N>
void SymmetricSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (storage_ != linalg::MatrixStorage::kDiagonal) {
    solve_factored(b, x);
    return;
  }
  Eigen::Index n = N;
  if constexpr (N == Eigen::Dynamic) n = inverse_diagonal_.size();
  x.resize(n);  // as the assignment it replaces: allocates only on a size change
  const double *inverse = inverse_diagonal_.data(), *rhs = b.data();
  double* out = x.data();
  for (Eigen::Index i = 0; i < n; ++i) out[i] = inverse[i] * rhs[i];
}

// True if A is positive definite (Cholesky succeeds). Not real-time safe.
bool is_positive_definite(const linalg::StructuralMatrix& A);

// Largest natural circular frequency sqrt(max eig(K, M)) in rad/s. Exact for dense
// models up to 400 DOF; otherwise an 80-step Lanczos estimate (top Ritz value plus its
// residual estimate). Not real-time safe.
double max_natural_frequency_rad_s(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness,
                                   const SymmetricSolver& mass_solver);

// Gershgorin upper bound of omega_max for a lumped (diagonal) mass; +infinity otherwise.
// Not real-time safe.
double frequency_upper_bound_rad_s(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness);

}  // namespace rpsd::integrators
