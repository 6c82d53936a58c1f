#include "rpsd/substructure/structural_matrix.h"

#include <cassert>
#include <stdexcept>
#include <utility>

namespace rpsd::substructure {
namespace {

// y += s A x by columns: an explicit loop so that no expression temporary can allocate.
void accumulate_sparse(const SparseMatrix& A, const Eigen::Ref<const Eigen::VectorXd>& x, double s,
                       Eigen::Ref<Eigen::VectorXd> y) noexcept {
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    const double sx = s * x[j];
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) y[it.row()] += it.value() * sx;
  }
}

}  // namespace

StructuralMatrix::StructuralMatrix(Eigen::MatrixXd dense) : storage_(std::move(dense)) {}

StructuralMatrix::StructuralMatrix(SparseMatrix sparse) : storage_(std::move(sparse)) {
  std::get<SparseMatrix>(storage_).makeCompressed();
}

Eigen::Index StructuralMatrix::rows() const noexcept {
  return std::visit([](const auto& m) { return m.rows(); }, storage_);
}

Eigen::Index StructuralMatrix::cols() const noexcept {
  return std::visit([](const auto& m) { return m.cols(); }, storage_);
}

const Eigen::MatrixXd& StructuralMatrix::dense() const {
  if (is_sparse()) throw std::logic_error("StructuralMatrix::dense(): the matrix is stored sparse");
  return std::get<Eigen::MatrixXd>(storage_);
}

const SparseMatrix& StructuralMatrix::sparse() const {
  if (!is_sparse()) throw std::logic_error("StructuralMatrix::sparse(): the matrix is stored dense");
  return std::get<SparseMatrix>(storage_);
}

Eigen::MatrixXd& StructuralMatrix::dense_mut() {
  if (is_sparse()) throw std::logic_error("StructuralMatrix::dense_mut(): the matrix is stored sparse");
  return std::get<Eigen::MatrixXd>(storage_);
}

SparseMatrix& StructuralMatrix::sparse_mut() {
  if (!is_sparse()) throw std::logic_error("StructuralMatrix::sparse_mut(): the matrix is stored dense");
  return std::get<SparseMatrix>(storage_);
}

Eigen::MatrixXd StructuralMatrix::to_dense() const {
  if (is_sparse()) return Eigen::MatrixXd(std::get<SparseMatrix>(storage_));
  return std::get<Eigen::MatrixXd>(storage_);
}

SparseMatrix StructuralMatrix::to_sparse() const {
  if (is_sparse()) return std::get<SparseMatrix>(storage_);
  // sparseView drops exact zeros only; keep every structural nonzero.
  SparseMatrix s = std::get<Eigen::MatrixXd>(storage_).sparseView(0.0, 0.0);
  s.makeCompressed();
  return s;
}

StructuralMatrix StructuralMatrix::converted(MatrixStorage storage) const {
  if (storage == MatrixStorage::sparse) return StructuralMatrix(to_sparse());
  return StructuralMatrix(to_dense());
}

double StructuralMatrix::coeff(Eigen::Index i, Eigen::Index j) const noexcept {
  if (is_sparse()) return std::get<SparseMatrix>(storage_).coeff(i, j);
  return std::get<Eigen::MatrixXd>(storage_)(i, j);
}

void StructuralMatrix::multiply(const Eigen::Ref<const Eigen::VectorXd>& x,
                                Eigen::Ref<Eigen::VectorXd> y) const noexcept {
  assert(x.size() == cols() && y.size() == rows());
  if (is_sparse()) {
    y.setZero();
    accumulate_sparse(std::get<SparseMatrix>(storage_), x, 1.0, y);
  } else {
    y.noalias() = std::get<Eigen::MatrixXd>(storage_) * x;
  }
}

void StructuralMatrix::multiply_add(const Eigen::Ref<const Eigen::VectorXd>& x, double s,
                                    Eigen::Ref<Eigen::VectorXd> y) const noexcept {
  assert(x.size() == cols() && y.size() == rows());
  if (is_sparse()) {
    accumulate_sparse(std::get<SparseMatrix>(storage_), x, s, y);
  } else {
    y.noalias() += s * std::get<Eigen::MatrixXd>(storage_) * x;
  }
}

StructuralMatrix StructuralMatrix::linear_combination(double a, const StructuralMatrix& A, double b,
                                                      const StructuralMatrix& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols()) {
    throw std::invalid_argument("StructuralMatrix::linear_combination: sizes differ");
  }
  if (A.is_sparse() || B.is_sparse()) {
    SparseMatrix s = a * A.to_sparse() + b * B.to_sparse();
    return StructuralMatrix(std::move(s));
  }
  return StructuralMatrix(Eigen::MatrixXd(a * A.dense() + b * B.dense()));
}

}  // namespace rpsd::substructure
