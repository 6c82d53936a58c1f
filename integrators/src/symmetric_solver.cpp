#include "rpsd/integrators/symmetric_solver.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::integrators {

SymmetricSolver::SymmetricSolver() = default;
SymmetricSolver::~SymmetricSolver() = default;
SymmetricSolver::SymmetricSolver(SymmetricSolver&&) noexcept = default;
SymmetricSolver& SymmetricSolver::operator=(SymmetricSolver&&) noexcept = default;

namespace {
[[noreturn]] void singular(std::string_view what, const std::string& detail) {
  throw std::invalid_argument(std::string(what) + " is singular (" + detail + ")");
}

// A pivot this small relative to the largest one means the factorisation is meaningless.
template <class Vec>
void check_pivots(const Vec& d, std::string_view what) {
  const double largest = d.cwiseAbs().maxCoeff();
  const double smallest = d.cwiseAbs().minCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest) || smallest <= 1e-14 * largest)
    singular(what, "a pivot of its LDL^T factorisation is zero or " +
                       std::to_string(smallest) + " against a largest of " + std::to_string(largest));
}
}  // namespace

void SymmetricSolver::factorize(const SystemMatrix& A, std::string_view what) {
  storage_ = A.storage();
  dense_.reset();
  sparse_amd_.reset();
  sparse_natural_.reset();
  switch (storage_) {
    case Storage::diagonal: {
      const auto& d = A.diagonal_values();
      if (d.size() == 0) singular(what, "it is empty");
      check_pivots(d, what);
      inverse_diagonal_ = d.cwiseInverse();
      return;
    }
    case Storage::dense: {
      dense_ = std::make_unique<Eigen::LDLT<Eigen::MatrixXd>>(A.dense());
      if (dense_->info() != Eigen::Success) singular(what, "LDL^T factorisation failed");
      check_pivots(dense_->vectorD(), what);
      return;
    }
    case Storage::sparse: {
      // Banded models factorise with less fill in their natural order; keep whichever
      // ordering gives the smaller factor, since every solve costs its non-zeros.
      sparse_amd_ = std::make_unique<SparseLdlt>(A.sparse());
      sparse_natural_ = std::make_unique<SparseLdltNatural>(A.sparse());
      const bool amd_ok = sparse_amd_->info() == Eigen::Success;
      const bool nat_ok = sparse_natural_->info() == Eigen::Success;
      if (!amd_ok && !nat_ok) singular(what, "sparse LDL^T factorisation failed");
      const auto nnz_amd = amd_ok ? sparse_amd_->matrixL().nestedExpression().nonZeros() : -1;
      const auto nnz_nat = nat_ok ? sparse_natural_->matrixL().nestedExpression().nonZeros() : -1;
      if (amd_ok && (!nat_ok || nnz_amd < nnz_nat)) {
        sparse_natural_.reset();
        check_pivots(sparse_amd_->vectorD(), what);
        work_.setZero(A.rows());
        inverse_diagonal_ = sparse_amd_->vectorD().cwiseInverse();  // vectorD() returns a copy
      } else {
        sparse_amd_.reset();
        check_pivots(sparse_natural_->vectorD(), what);
      }
      return;
    }
  }
}

void SymmetricSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  switch (storage_) {
    case Storage::diagonal: x.array() = inverse_diagonal_.array() * b.array(); break;
    case Storage::dense: x = dense_->solve(b); break;
    case Storage::sparse:
      if (sparse_amd_) {
        // P^T L D L^T P x = b
        work_.noalias() = sparse_amd_->permutationP() * b;
        sparse_amd_->matrixL().solveInPlace(work_);
        work_.array() *= inverse_diagonal_.array();
        sparse_amd_->matrixU().solveInPlace(work_);
        x.noalias() = sparse_amd_->permutationPinv() * work_;
      } else {
        x = sparse_natural_->solve(b);
      }
      break;
  }
}

Eigen::Index SymmetricSolver::factor_nonzeros() const {
  switch (storage_) {
    case Storage::diagonal: return inverse_diagonal_.size();
    case Storage::dense: return dense_->matrixLDLT().rows() * (dense_->matrixLDLT().rows() + 1) / 2;
    case Storage::sparse:
      return sparse_amd_ ? sparse_amd_->matrixL().nestedExpression().nonZeros() + sparse_amd_->rows()
                         : sparse_natural_->matrixL().nestedExpression().nonZeros() +
                               sparse_natural_->rows();
  }
  return 0;
}

bool is_positive_definite(const SystemMatrix& A) {
  switch (A.storage()) {
    case Storage::diagonal:
      return A.diagonal_values().size() > 0 && (A.diagonal_values().array() > 0.0).all();
    case Storage::dense: {
      Eigen::LLT<Eigen::MatrixXd> llt(A.dense());
      return llt.info() == Eigen::Success;
    }
    case Storage::sparse: {
      Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(A.sparse());
      return llt.info() == Eigen::Success;
    }
  }
  return false;
}

double frequency_upper_bound_rad_s(const SystemMatrix& mass, const SystemMatrix& stiffness) {
  if (mass.storage() != Storage::diagonal) return std::numeric_limits<double>::infinity();
  // Gershgorin's theorem on M^-1/2 K M^-1/2.
  const Eigen::VectorXd s = mass.diagonal_values().cwiseSqrt().cwiseInverse();
  switch (stiffness.storage()) {
    case Storage::diagonal:
      return std::sqrt((stiffness.diagonal_values().cwiseAbs().array() * s.array().square()).maxCoeff());
    case Storage::dense:
      return std::sqrt(
          (s.asDiagonal() * stiffness.dense().cwiseAbs() * s).maxCoeff());
    case Storage::sparse: {
      Eigen::VectorXd row = Eigen::VectorXd::Zero(mass.rows());
      const auto& k = stiffness.sparse();
      for (int c = 0; c < k.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(k, c); it; ++it)
          row(it.row()) += std::abs(it.value()) * s(it.row()) * s(it.col());
      return std::sqrt(row.maxCoeff());
    }
  }
  return std::numeric_limits<double>::infinity();
}

double max_natural_frequency_rad_s(const SystemMatrix& mass, const SystemMatrix& stiffness,
                                   const SymmetricSolver& mass_solver) {
  const Eigen::Index n = mass.rows();
  if (stiffness.max_abs() == 0.0) return 0.0;
  if (n <= 400 && mass.storage() != Storage::sparse && stiffness.storage() != Storage::sparse) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
        stiffness.to_dense(), mass.to_dense(), Eigen::EigenvaluesOnly);
    if (es.info() == Eigen::Success) return std::sqrt(std::max(0.0, es.eigenvalues().maxCoeff()));
  }
  // Lanczos on M^-1 K in the M inner product with full reorthogonalisation. The extreme
  // Ritz value converges fast; adding the residual estimate |beta_m s_m| keeps it from
  // underestimating.
  const Eigen::Index m = std::min<Eigen::Index>(n, 80);
  Eigen::MatrixXd V(n, m + 1), MV(n, m + 1);
  Eigen::VectorXd alpha = Eigen::VectorXd::Zero(m), beta = Eigen::VectorXd::Zero(m + 1);
  Eigen::VectorXd q(n), mq(n), kq(n), w(n);
  for (Eigen::Index i = 0; i < n; ++i)
    q(i) = ((i % 2) ? -1.0 : 1.0) * (1.0 + 0.37 * std::sin(1.7 * static_cast<double>(i)));
  mass.multiply(q, mq);
  const double norm0 = std::sqrt(q.dot(mq));
  V.col(0) = q / norm0;
  MV.col(0) = mq / norm0;
  Eigen::Index steps = 0;
  for (Eigen::Index j = 0; j < m; ++j) {
    q = V.col(j);
    stiffness.multiply(q, kq);
    alpha(j) = q.dot(kq);
    mass_solver.solve(kq, w);  // w = M^-1 K q_j
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index i = 0; i <= j; ++i) w -= MV.col(i).dot(w) * V.col(i);
    mass.multiply(w, mq);
    beta(j + 1) = std::sqrt(std::max(0.0, w.dot(mq)));
    steps = j + 1;
    if (beta(j + 1) <= 1e-10 * std::abs(alpha(j))) break;
    V.col(j + 1) = w / beta(j + 1);
    MV.col(j + 1) = mq / beta(j + 1);
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(steps, steps);
  for (Eigen::Index j = 0; j < steps; ++j) {
    T(j, j) = alpha(j);
    if (j + 1 < steps) T(j, j + 1) = T(j + 1, j) = beta(j + 1);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> tes(T);
  const Eigen::Index top = steps - 1;
  const double theta = tes.eigenvalues()(top);
  const double residual = std::abs(beta(steps) * tes.eigenvectors()(steps - 1, top));
  return std::sqrt(std::max(0.0, theta + residual));
}

}  // namespace rpsd::integrators
