#include "rpsd/integrators/symmetric_solver.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
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

double max_natural_frequency_rad_s(const SystemMatrix& mass, const SystemMatrix& stiffness,
                                   const SymmetricSolver& mass_solver) {
  const Eigen::Index n = mass.rows();
  if (stiffness.max_abs() == 0.0) return 0.0;
  if (n <= 400 && mass.storage() != Storage::sparse && stiffness.storage() != Storage::sparse) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
        stiffness.to_dense(), mass.to_dense(), Eigen::EigenvaluesOnly);
    if (es.info() == Eigen::Success) return std::sqrt(std::max(0.0, es.eigenvalues().maxCoeff()));
  }
  // Power iteration on M^-1 K; an alternating start vector weights the stiff modes.
  Eigen::VectorXd x(n), kx(n), mx(n);
  for (Eigen::Index i = 0; i < n; ++i)
    x(i) = ((i % 2) ? -1.0 : 1.0) * (1.0 + 0.37 * std::sin(1.7 * static_cast<double>(i)));
  double lambda = 0.0;
  for (int it = 0; it < 20000; ++it) {
    stiffness.multiply(x, kx);
    mass.multiply(x, mx);
    const double rq = x.dot(kx) / x.dot(mx);
    mass_solver.solve(kx, x);
    x /= x.norm();
    if (it > 10 && std::abs(rq - lambda) <= 1e-12 * std::abs(rq)) {
      lambda = rq;
      break;
    }
    lambda = rq;
  }
  return std::sqrt(std::max(0.0, lambda));
}

}  // namespace rpsd::integrators
