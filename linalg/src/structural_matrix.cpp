#include "rpsd/linalg/structural_matrix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rpsd::linalg {
namespace {

bool has_off_diagonal(const Eigen::MatrixXd& a) {
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (i != j && a(i, j) != 0.0) return true;
  return false;
}

bool has_off_diagonal(const SparseMatrix& a) {
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0) return true;
  return false;
}

MatrixStorage most_general(MatrixStorage a, MatrixStorage b) { return std::max(a, b); }

void require_same_size(const StructuralMatrix& A, const StructuralMatrix& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols()) {
    throw std::invalid_argument("StructuralMatrix::linear_combination: matrix sizes differ");
  }
}

}  // namespace

StructuralMatrix::StructuralMatrix(Eigen::MatrixXd dense)
    : storage_(MatrixStorage::kDense), rows_(dense.rows()), cols_(dense.cols()), dense_(std::move(dense)) {}

StructuralMatrix::StructuralMatrix(SparseMatrix sparse)
    : storage_(MatrixStorage::kSparse), rows_(sparse.rows()), cols_(sparse.cols()) {
  sparse_.swap(sparse);  // Eigen 3.4's SparseMatrix has no move constructor
  sparse_.makeCompressed();
  sparse_rows_ = sparse_;
  sparse_rows_.makeCompressed();
  row_major_position_.resize(static_cast<std::size_t>(sparse_.nonZeros()));
  for (Eigen::Index j = 0; j < sparse_.outerSize(); ++j) {
    for (Eigen::Index k = sparse_.outerIndexPtr()[j]; k < sparse_.outerIndexPtr()[j + 1]; ++k) {
      const Eigen::Index i = sparse_.innerIndexPtr()[k];
      const auto* first = sparse_rows_.innerIndexPtr() + sparse_rows_.outerIndexPtr()[i];
      const auto* last = sparse_rows_.innerIndexPtr() + sparse_rows_.outerIndexPtr()[i + 1];
      row_major_position_[static_cast<std::size_t>(k)] =
          std::lower_bound(first, last, j) - sparse_rows_.innerIndexPtr();
    }
  }
}

StructuralMatrix StructuralMatrix::diagonal(Eigen::VectorXd values) {
  StructuralMatrix m;
  m.storage_ = MatrixStorage::kDiagonal;
  m.rows_ = m.cols_ = values.size();
  m.diagonal_ = std::move(values);
  return m;
}

void StructuralMatrix::values_changed() noexcept {
  if (storage_ != MatrixStorage::kSparse) return;
  const double* values = sparse_.valuePtr();
  double* row_values = sparse_rows_.valuePtr();
  for (std::size_t k = 0; k < row_major_position_.size(); ++k) row_values[row_major_position_[k]] = values[k];
}

StructuralMatrix StructuralMatrix::compacted() const {
  const bool square = rows_ == cols_;
  switch (storage_) {
    case MatrixStorage::kDiagonal:
      return *this;
    case MatrixStorage::kDense:
      if (square && !has_off_diagonal(dense_)) return diagonal(dense_.diagonal());
      return *this;
    case MatrixStorage::kSparse: {
      if (square && !has_off_diagonal(sparse_)) {
        Eigen::VectorXd d = Eigen::VectorXd::Zero(rows_);
        for (Eigen::Index k = 0; k < sparse_.outerSize(); ++k)
          for (SparseMatrix::InnerIterator it(sparse_, k); it; ++it)
            if (it.row() == it.col()) d(it.row()) += it.value();
        return diagonal(std::move(d));
      }
      SparseMatrix pruned = sparse_;
      pruned.prune(0.0);
      return StructuralMatrix(pruned);
    }
  }
  return *this;
}

StructuralMatrix StructuralMatrix::converted(MatrixStorage storage) const {
  switch (storage) {
    case MatrixStorage::kDense:
      return StructuralMatrix(to_dense());
    case MatrixStorage::kSparse:
      return StructuralMatrix(to_sparse());
    case MatrixStorage::kDiagonal: {
      const StructuralMatrix c = compacted();
      if (!c.is_diagonal()) throw std::invalid_argument("StructuralMatrix::converted: the matrix is not diagonal");
      return c;
    }
  }
  return *this;
}

StructuralMatrix StructuralMatrix::linear_combination(double a, const StructuralMatrix& A, double b,
                                                      const StructuralMatrix& B) {
  require_same_size(A, B);
  switch (most_general(A.storage_, B.storage_)) {
    case MatrixStorage::kDiagonal:
      return diagonal(a * A.diagonal_ + b * B.diagonal_);
    case MatrixStorage::kDense:
      return StructuralMatrix(Eigen::MatrixXd(a * A.to_dense() + b * B.to_dense()));
    case MatrixStorage::kSparse:
      return StructuralMatrix(SparseMatrix(a * A.to_sparse() + b * B.to_sparse()));
  }
  return {};
}

StructuralMatrix StructuralMatrix::linear_combination(double a, const StructuralMatrix& A, double b,
                                                      const StructuralMatrix& B, double c, const StructuralMatrix& C) {
  require_same_size(A, B);
  require_same_size(A, C);
  switch (most_general(most_general(A.storage_, B.storage_), C.storage_)) {
    case MatrixStorage::kDiagonal:
      return diagonal(a * A.diagonal_ + b * B.diagonal_ + c * C.diagonal_);
    case MatrixStorage::kDense:
      return StructuralMatrix(Eigen::MatrixXd(a * A.to_dense() + b * B.to_dense() + c * C.to_dense()));
    case MatrixStorage::kSparse:
      return StructuralMatrix(SparseMatrix(a * A.to_sparse() + b * B.to_sparse() + c * C.to_sparse()));
  }
  return {};
}

const Eigen::VectorXd& StructuralMatrix::diagonal_values() const {
  if (storage_ != MatrixStorage::kDiagonal)
    throw std::logic_error("StructuralMatrix::diagonal_values(): not stored diagonal");
  return diagonal_;
}

const Eigen::MatrixXd& StructuralMatrix::dense() const {
  if (storage_ != MatrixStorage::kDense) throw std::logic_error("StructuralMatrix::dense(): not stored dense");
  return dense_;
}

const SparseMatrix& StructuralMatrix::sparse() const {
  if (storage_ != MatrixStorage::kSparse) throw std::logic_error("StructuralMatrix::sparse(): not stored sparse");
  return sparse_;
}

Eigen::MatrixXd& StructuralMatrix::dense_mut() {
  if (storage_ != MatrixStorage::kDense) throw std::logic_error("StructuralMatrix::dense_mut(): not stored dense");
  return dense_;
}

SparseMatrix& StructuralMatrix::sparse_mut() {
  if (storage_ != MatrixStorage::kSparse) throw std::logic_error("StructuralMatrix::sparse_mut(): not stored sparse");
  return sparse_;
}

Eigen::MatrixXd StructuralMatrix::to_dense() const {
  switch (storage_) {
    case MatrixStorage::kDiagonal:
      return diagonal_.asDiagonal();
    case MatrixStorage::kDense:
      return dense_;
    case MatrixStorage::kSparse:
      return Eigen::MatrixXd(sparse_);
  }
  return {};
}

SparseMatrix StructuralMatrix::to_sparse() const {
  switch (storage_) {
    case MatrixStorage::kDiagonal: {
      SparseMatrix s(rows_, cols_);
      s.reserve(Eigen::VectorXi::Constant(cols_, 1));
      for (Eigen::Index i = 0; i < diagonal_.size(); ++i)
        if (diagonal_(i) != 0.0) s.insert(i, i) = diagonal_(i);
      s.makeCompressed();
      return s;
    }
    case MatrixStorage::kDense: {
      // Every nonzero kept, whatever its size.
      SparseMatrix s = dense_.sparseView(0.0, 0.0);
      s.makeCompressed();
      return s;
    }
    case MatrixStorage::kSparse:
      return sparse_;
  }
  return {};
}

double StructuralMatrix::coeff(Eigen::Index i, Eigen::Index j) const noexcept {
  switch (storage_) {
    case MatrixStorage::kDiagonal:
      return i == j ? diagonal_[i] : 0.0;
    case MatrixStorage::kDense:
      return dense_(i, j);
    case MatrixStorage::kSparse:
      return sparse_.coeff(i, j);
  }
  return 0.0;
}

// The dense and sparse products (the diagonal and one-DOF arms are inline in the header).
void StructuralMatrix::multiply_stored(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       Eigen::Ref<Eigen::VectorXd> y) const noexcept {
  if (storage_ == MatrixStorage::kSparse) {
    y.noalias() = sparse_rows_ * x;
  } else {
    y.noalias() = dense_ * x;
  }
}

void StructuralMatrix::multiply_add_stored(double s, const Eigen::Ref<const Eigen::VectorXd>& x,
                                           Eigen::Ref<Eigen::VectorXd> y) const noexcept {
  if (storage_ == MatrixStorage::kSparse) {
    y.noalias() += s * (sparse_rows_ * x);
  } else {
    y.noalias() += s * (dense_ * x);
  }
}

double StructuralMatrix::max_abs() const {
  double m = 0.0;
  for_each_entry([&](Eigen::Index, Eigen::Index, double v) { m = std::max(m, std::abs(v)); });
  return m;
}

bool StructuralMatrix::is_symmetric(double rel_tol) const {
  if (rows_ != cols_) return false;
  const double tol = rel_tol * max_abs();
  switch (storage_) {
    case MatrixStorage::kDiagonal:
      return true;
    case MatrixStorage::kDense:
      return dense_.size() == 0 || (dense_ - dense_.transpose()).cwiseAbs().maxCoeff() <= tol;
    case MatrixStorage::kSparse: {
      const SparseMatrix d = sparse_ - SparseMatrix(sparse_.transpose());
      for (Eigen::Index k = 0; k < d.outerSize(); ++k)
        for (SparseMatrix::InnerIterator it(d, k); it; ++it)
          if (std::abs(it.value()) > tol) return false;
      return true;
    }
  }
  return false;
}

bool StructuralMatrix::all_finite() const {
  switch (storage_) {
    case MatrixStorage::kDiagonal:
      return diagonal_.allFinite();
    case MatrixStorage::kDense:
      return dense_.allFinite();
    case MatrixStorage::kSparse:
      return Eigen::Map<const Eigen::VectorXd>(sparse_.valuePtr(), sparse_.nonZeros()).allFinite();
  }
  return false;
}

}  // namespace rpsd::linalg
