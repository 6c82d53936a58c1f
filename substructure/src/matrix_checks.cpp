#include "matrix_checks.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rpsd::substructure::detail {
namespace {

std::string entry(Eigen::Index i, Eigen::Index j) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "[%lld,%lld]", static_cast<long long>(i), static_cast<long long>(j));
  return buf;
}

}  // namespace

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

void require_square(const linalg::StructuralMatrix& A, const std::string& what) {
  if (A.rows() == 0 || A.cols() == 0) throw std::invalid_argument(what + " is empty");
  if (A.rows() != A.cols()) {
    throw std::invalid_argument(what + " is not square: " + std::to_string(A.rows()) + " rows x " +
                                std::to_string(A.cols()) + " columns");
  }
}

void require_size(const linalg::StructuralMatrix& A, Eigen::Index n, const std::string& what) {
  if (A.rows() != n || A.cols() != n) {
    throw std::invalid_argument(what + " is " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) +
                                " but the model has " + std::to_string(n) + " DOFs");
  }
}

void require_finite(const linalg::StructuralMatrix& A, const std::string& what) {
  A.for_each_entry([&](Eigen::Index i, Eigen::Index j, double v) {
    if (!std::isfinite(v)) {
      throw std::invalid_argument(what + " has a non-finite entry " + entry(i, j) + " = " + fmt(v));
    }
  });
}

void require_symmetric(const linalg::StructuralMatrix& A, const std::string& what, double rel_tol) {
  double max_abs = 0.0;
  A.for_each_entry([&](Eigen::Index, Eigen::Index, double v) { max_abs = std::max(max_abs, std::abs(v)); });
  double worst = 0.0;
  Eigen::Index wi = 0, wj = 0;
  if (A.is_sparse()) {
    const linalg::SparseMatrix diff = A.sparse() - linalg::SparseMatrix(A.sparse().transpose());
    for (Eigen::Index j = 0; j < diff.outerSize(); ++j)
      for (linalg::SparseMatrix::InnerIterator it(diff, j); it; ++it)
        if (std::abs(it.value()) > worst) {
          worst = std::abs(it.value());
          wi = it.row();
          wj = it.col();
        }
  } else if (!A.is_diagonal()) {
    const Eigen::MatrixXd& d = A.dense();
    for (Eigen::Index j = 0; j < d.cols(); ++j)
      for (Eigen::Index i = j + 1; i < d.rows(); ++i)
        if (std::abs(d(i, j) - d(j, i)) > worst) {
          worst = std::abs(d(i, j) - d(j, i));
          wi = i;
          wj = j;
        }
  }
  if (worst > rel_tol * max_abs) {
    throw std::invalid_argument(what + " is not symmetric: " + entry(wi, wj) + " = " + fmt(A.coeff(wi, wj)) + " but " +
                                entry(wj, wi) + " = " + fmt(A.coeff(wj, wi)));
  }
}

void require_nonnegative_diagonal(const linalg::StructuralMatrix& A, const std::string& what) {
  const Eigen::Index n = std::min(A.rows(), A.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = A.coeff(i, i);
    if (v < 0.0) {
      throw std::invalid_argument(what + " has a negative diagonal entry " + entry(i, i) + " = " + fmt(v));
    }
  }
}

void require_positive_definite(const linalg::StructuralMatrix& A, const std::string& what) {
  const Eigen::Index n = A.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = A.coeff(i, i);
    if (!(v > 0.0)) {
      throw std::invalid_argument(what + " is not positive definite: diagonal entry " + entry(i, i) + " = " + fmt(v) +
                                  (v == 0.0 ? " (a DOF without mass or stiffness)" : ""));
    }
  }
  bool ok = false;
  if (A.is_sparse()) {
    Eigen::SimplicialLLT<linalg::SparseMatrix, Eigen::Lower> llt(A.sparse());
    ok = llt.info() == Eigen::Success;
  } else if (A.is_diagonal()) {
    ok = true;  // every diagonal entry is positive (checked above)
  } else {
    Eigen::LLT<Eigen::MatrixXd> llt(A.dense());
    ok = llt.info() == Eigen::Success;
  }
  if (!ok) {
    throw std::invalid_argument(what + " is not positive definite: its Cholesky factorisation failed");
  }
}

}  // namespace rpsd::substructure::detail
