#include "rpsd/integrators/system_matrix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rpsd::integrators {

SystemMatrix SystemMatrix::from_dense(const Eigen::MatrixXd& a) {
  SystemMatrix m;
  m.rows_ = a.rows();
  m.cols_ = a.cols();
  const bool square = a.rows() == a.cols();
  bool diagonal = square;
  for (Eigen::Index j = 0; diagonal && j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (i != j && a(i, j) != 0.0) {
        diagonal = false;
        break;
      }
  if (diagonal) {
    m.storage_ = Storage::diagonal;
    m.diag_ = a.diagonal();
  } else {
    m.storage_ = Storage::dense;
    m.dense_ = a;
  }
  return m;
}

SystemMatrix SystemMatrix::from_sparse(const Eigen::SparseMatrix<double>& a) {
  SystemMatrix m;
  m.rows_ = a.rows();
  m.cols_ = a.cols();
  bool diagonal = a.rows() == a.cols();
  for (int k = 0; diagonal && k < a.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0) {
        diagonal = false;
        break;
      }
  if (diagonal) {
    m.storage_ = Storage::diagonal;
    m.diag_ = Eigen::VectorXd::Zero(a.rows());
    for (int k = 0; k < a.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it)
        if (it.row() == it.col()) m.diag_(it.row()) += it.value();
  } else {
    m.storage_ = Storage::sparse;
    m.sparse_ = a;
    m.sparse_.prune(0.0);
    m.sparse_.makeCompressed();
    m.sparse_rows_ = m.sparse_;
    m.sparse_rows_.makeCompressed();
  }
  return m;
}

SystemMatrix SystemMatrix::combine(double a, const SystemMatrix& A, double b,
                                   const SystemMatrix& B, double c, const SystemMatrix& C) {
  if (A.rows_ != B.rows_ || A.rows_ != C.rows_ || A.cols_ != B.cols_ || A.cols_ != C.cols_)
    throw std::invalid_argument("SystemMatrix::combine: matrix sizes differ");
  const auto most_general = std::max({A.storage_, B.storage_, C.storage_});
  if (most_general == Storage::diagonal) {
    SystemMatrix m;
    m.rows_ = A.rows_;
    m.cols_ = A.cols_;
    m.diag_ = a * A.diag_ + b * B.diag_ + c * C.diag_;
    return m;
  }
  if (most_general == Storage::dense)
    return from_dense(a * A.to_dense() + b * B.to_dense() + c * C.to_dense());
  Eigen::SparseMatrix<double> s = a * A.to_sparse() + b * B.to_sparse() + c * C.to_sparse();
  return from_sparse(s);
}

void SystemMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  switch (storage_) {
    case Storage::diagonal: y.array() = diag_.array() * x.array(); break;
    case Storage::dense: y.noalias() = dense_ * x; break;
    case Storage::sparse: y.noalias() = sparse_rows_ * x; break;
  }
}

void SystemMatrix::multiply_add(double s, const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  switch (storage_) {
    case Storage::diagonal: y.array() += s * diag_.array() * x.array(); break;
    case Storage::dense: y.noalias() += s * (dense_ * x); break;
    case Storage::sparse: y.noalias() += s * (sparse_rows_ * x); break;
  }
}

double SystemMatrix::max_abs() const {
  switch (storage_) {
    case Storage::diagonal: return diag_.size() ? diag_.cwiseAbs().maxCoeff() : 0.0;
    case Storage::dense: return dense_.size() ? dense_.cwiseAbs().maxCoeff() : 0.0;
    case Storage::sparse: {
      double m = 0.0;
      for (int k = 0; k < sparse_.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(sparse_, k); it; ++it)
          m = std::max(m, std::abs(it.value()));
      return m;
    }
  }
  return 0.0;
}

bool SystemMatrix::is_symmetric(double rel_tol) const {
  if (rows_ != cols_) return false;
  const double tol = rel_tol * max_abs();
  switch (storage_) {
    case Storage::diagonal: return true;
    case Storage::dense:
      return (dense_ - dense_.transpose()).cwiseAbs().maxCoeff() <= tol;
    case Storage::sparse: {
      const Eigen::SparseMatrix<double> d = sparse_ - Eigen::SparseMatrix<double>(sparse_.transpose());
      for (int k = 0; k < d.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(d, k); it; ++it)
          if (std::abs(it.value()) > tol) return false;
      return true;
    }
  }
  return false;
}

bool SystemMatrix::all_finite() const {
  switch (storage_) {
    case Storage::diagonal: return diag_.allFinite();
    case Storage::dense: return dense_.allFinite();
    case Storage::sparse:
      return Eigen::Map<const Eigen::VectorXd>(sparse_.valuePtr(), sparse_.nonZeros()).allFinite();
  }
  return false;
}

Eigen::MatrixXd SystemMatrix::to_dense() const {
  switch (storage_) {
    case Storage::diagonal: return diag_.asDiagonal();
    case Storage::dense: return dense_;
    case Storage::sparse: return Eigen::MatrixXd(sparse_);
  }
  return {};
}

Eigen::SparseMatrix<double> SystemMatrix::to_sparse() const {
  switch (storage_) {
    case Storage::diagonal: {
      Eigen::SparseMatrix<double> s(rows_, cols_);
      s.reserve(Eigen::VectorXi::Constant(cols_, 1));
      for (Eigen::Index i = 0; i < diag_.size(); ++i)
        if (diag_(i) != 0.0) s.insert(i, i) = diag_(i);
      s.makeCompressed();
      return s;
    }
    case Storage::dense: return dense_.sparseView();
    case Storage::sparse: return sparse_;
  }
  return {};
}

}  // namespace rpsd::integrators
