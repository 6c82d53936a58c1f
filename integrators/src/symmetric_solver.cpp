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
    singular(what, "a pivot of its LDL^T factorisation is zero or " + std::to_string(smallest) +
                       " against a largest of " + std::to_string(largest));
}
}  // namespace

void SymmetricSolver::factorize(const linalg::StructuralMatrix& A, std::string_view what) {
  storage_ = A.storage();
  dense_.reset();
  sparse_amd_.reset();
  band_ = -1;
  band_l_.resize(0, 0);
  switch (storage_) {
    case linalg::MatrixStorage::kDiagonal: {
      const auto& d = A.diagonal_values();
      if (d.size() == 0) singular(what, "it is empty");
      check_pivots(d, what);
      inverse_diagonal_ = d.cwiseInverse();
      return;
    }
    case linalg::MatrixStorage::kDense: {
      dense_ = std::make_unique<Eigen::LDLT<Eigen::MatrixXd>>(A.dense());
      if (dense_->info() != Eigen::Success) singular(what, "LDL^T factorisation failed");
      check_pivots(dense_->vectorD(), what);
      return;
    }
    case linalg::MatrixStorage::kSparse: {
      const auto& a = A.sparse();
      Eigen::Index b = 0;
      for (int k = 0; k < a.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it)
          b = std::max<Eigen::Index>(b, std::abs(it.row() - it.col()));
      // Reordering cannot beat the band by much for frame-like models; when AMD's factor
      // is not clearly smaller than the band, the contiguous band solver is faster.
      sparse_amd_ = std::make_unique<SparseLdlt>(a);
      const bool amd_ok = sparse_amd_->info() == Eigen::Success;
      const auto nnz_amd = amd_ok ? sparse_amd_->matrixL().nestedExpression().nonZeros() : 0;
      if (b <= 256 && (!amd_ok || A.rows() * b <= 2 * nnz_amd)) {
        sparse_amd_.reset();
        factorize_band(a, b, what);
        return;
      }
      if (!amd_ok) singular(what, "sparse LDL^T factorisation failed");
      check_pivots(sparse_amd_->vectorD(), what);
      work_.setZero(A.rows());
      inverse_diagonal_ = sparse_amd_->vectorD().cwiseInverse();  // vectorD() returns a copy
      return;
    }
  }
}

void SymmetricSolver::factorize_band(const Eigen::SparseMatrix<double>& a, Eigen::Index b, std::string_view what) {
  const Eigen::Index n = a.rows();
  band_ = b;
  band_l_.setZero(n, std::max<Eigen::Index>(b, 1));
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  // Lower triangle of A into the band (column j of row i at position j - i + b).
  for (int k = 0; k < a.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it) {
      if (it.row() == it.col())
        d(it.row()) += it.value();
      else if (it.row() > it.col())
        band_l_(it.row(), it.col() - it.row() + b) += it.value();
    }
  // Row-oriented LDL^T: L(i,j) = (A(i,j) - sum_k L(i,k) D(k) L(j,k)) / D(j).
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j0 = std::max<Eigen::Index>(0, i - b);
    for (Eigen::Index j = j0; j < i; ++j) {
      double sum = band_l_(i, j - i + b);
      const Eigen::Index k0 = std::max(j0, j - b);
      for (Eigen::Index k = k0; k < j; ++k) sum -= band_l_(i, k - i + b) * d(k) * band_l_(j, k - j + b);
      band_l_(i, j - i + b) = sum / d(j);
    }
    double di = d(i);
    for (Eigen::Index k = j0; k < i; ++k) {
      const double l = band_l_(i, k - i + b);
      di -= l * l * d(k);
    }
    d(i) = di;
  }
  check_pivots(d, what);
  inverse_diagonal_ = d.cwiseInverse();
}

void SymmetricSolver::solve_band(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) const {
  const Eigen::Index n = x.size();
  const Eigen::Index b = band_;
  x = rhs;
  for (Eigen::Index i = 1; i < n; ++i) {  // L y = rhs: contiguous dot products
    const Eigen::Index len = std::min(i, b);
    x(i) -= band_l_.row(i).tail(len).dot(x.segment(i - len, len).transpose());
  }
  x.array() *= inverse_diagonal_.array();
  for (Eigen::Index i = n - 1; i > 0; --i) {  // L^T x = z: contiguous axpys
    const Eigen::Index len = std::min(i, b);
    x.segment(i - len, len) -= x(i) * band_l_.row(i).tail(len).transpose();
  }
}

void SymmetricSolver::solve_factored(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  switch (storage_) {
    case linalg::MatrixStorage::kDiagonal:  // inline in the header
      break;
    case linalg::MatrixStorage::kDense:
      x = dense_->solve(b);
      break;
    case linalg::MatrixStorage::kSparse:
      if (band_ >= 0) {
        solve_band(b, x);
      } else if (sparse_amd_) {
        // P^T L D L^T P x = b
        work_.noalias() = sparse_amd_->permutationP() * b;
        sparse_amd_->matrixL().solveInPlace(work_);
        work_.array() *= inverse_diagonal_.array();
        sparse_amd_->matrixU().solveInPlace(work_);
        x.noalias() = sparse_amd_->permutationPinv() * work_;
      }
      break;
  }
}

Eigen::Index SymmetricSolver::factor_nonzeros() const {
  switch (storage_) {
    case linalg::MatrixStorage::kDiagonal:
      return inverse_diagonal_.size();
    case linalg::MatrixStorage::kDense:
      return dense_->matrixLDLT().rows() * (dense_->matrixLDLT().rows() + 1) / 2;
    case linalg::MatrixStorage::kSparse:
      if (band_ >= 0) return band_l_.rows() * (band_ + 1);
      return sparse_amd_->matrixL().nestedExpression().nonZeros() + sparse_amd_->rows();
  }
  return 0;
}

bool is_positive_definite(const linalg::StructuralMatrix& A) {
  switch (A.storage()) {
    case linalg::MatrixStorage::kDiagonal:
      return A.diagonal_values().size() > 0 && (A.diagonal_values().array() > 0.0).all();
    case linalg::MatrixStorage::kDense: {
      Eigen::LLT<Eigen::MatrixXd> llt(A.dense());
      return llt.info() == Eigen::Success;
    }
    case linalg::MatrixStorage::kSparse: {
      Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(A.sparse());
      return llt.info() == Eigen::Success;
    }
  }
  return false;
}

double frequency_upper_bound_rad_s(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness) {
  if (mass.storage() != linalg::MatrixStorage::kDiagonal) return std::numeric_limits<double>::infinity();
  // Gershgorin's theorem on M^-1/2 K M^-1/2.
  const Eigen::VectorXd s = mass.diagonal_values().cwiseSqrt().cwiseInverse();
  switch (stiffness.storage()) {
    case linalg::MatrixStorage::kDiagonal:
      return std::sqrt((stiffness.diagonal_values().cwiseAbs().array() * s.array().square()).maxCoeff());
    case linalg::MatrixStorage::kDense:
      return std::sqrt((s.asDiagonal() * stiffness.dense().cwiseAbs() * s).maxCoeff());
    case linalg::MatrixStorage::kSparse: {
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

double max_natural_frequency_rad_s(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness,
                                   const SymmetricSolver& mass_solver) {
  const Eigen::Index n = mass.rows();
  if (stiffness.max_abs() == 0.0) return 0.0;
  if (n <= 400 && mass.storage() != linalg::MatrixStorage::kSparse &&
      stiffness.storage() != linalg::MatrixStorage::kSparse) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(stiffness.to_dense(), mass.to_dense(),
                                                                 Eigen::EigenvaluesOnly);
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
