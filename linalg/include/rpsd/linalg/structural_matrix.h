// A structural matrix (mass, damping, stiffness) in the storage that represents it: diagonal
// (lumped mass, no damping), dense (small models) or sparse (large models). The numerical
// models build it and the integration schemes take it, so there is one type for one idea.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cassert>
#include <concepts>
#include <cstdint>
#include <vector>

namespace rpsd::linalg {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, compressed

enum class MatrixStorage : std::uint8_t { kDiagonal, kDense, kSparse };

class StructuralMatrix {
 public:
  StructuralMatrix() = default;  // 0 x 0, dense
  // Stored as given. Not real-time safe.
  explicit StructuralMatrix(Eigen::MatrixXd dense);
  explicit StructuralMatrix(SparseMatrix sparse);
  static StructuralMatrix diagonal(Eigen::VectorXd values);

  // The cheapest exact storage: a square matrix with nothing off its diagonal keeps only the
  // diagonal; a sparse one drops its explicit zeros. Not real-time safe.
  [[nodiscard]] StructuralMatrix compacted() const;
  // The same matrix in the requested storage (a non-diagonal matrix cannot become diagonal:
  // std::invalid_argument). Not real-time safe.
  [[nodiscard]] StructuralMatrix converted(MatrixStorage storage) const;
  // a A + b B (+ c C) in the most general storage of the operands. Sizes must agree
  // (std::invalid_argument). Not real-time safe.
  [[nodiscard]] static StructuralMatrix linear_combination(double a, const StructuralMatrix& A, double b,
                                                           const StructuralMatrix& B);
  [[nodiscard]] static StructuralMatrix linear_combination(double a, const StructuralMatrix& A, double b,
                                                           const StructuralMatrix& B, double c,
                                                           const StructuralMatrix& C);

  [[nodiscard]] MatrixStorage storage() const noexcept { return storage_; }
  [[nodiscard]] bool is_sparse() const noexcept { return storage_ == MatrixStorage::kSparse; }
  [[nodiscard]] bool is_diagonal() const noexcept { return storage_ == MatrixStorage::kDiagonal; }
  [[nodiscard]] Eigen::Index rows() const noexcept { return rows_; }
  [[nodiscard]] Eigen::Index cols() const noexcept { return cols_; }

  // The stored representation; std::logic_error when the matrix is stored another way.
  [[nodiscard]] const Eigen::VectorXd& diagonal_values() const;
  [[nodiscard]] const Eigen::MatrixXd& dense() const;
  [[nodiscard]] const SparseMatrix& sparse() const;
  // In-place value updates that keep the storage and the sparsity pattern. After changing
  // values through sparse_mut(), call values_changed() before the next product.
  [[nodiscard]] Eigen::MatrixXd& dense_mut();
  [[nodiscard]] SparseMatrix& sparse_mut();
  // Copies the sparse values into the row-major copy the products use. Real-time safe.
  void values_changed() noexcept;

  // Copies in another representation. Not real-time safe.
  [[nodiscard]] Eigen::MatrixXd to_dense() const;
  [[nodiscard]] SparseMatrix to_sparse() const;

  // Entry (i, j); O(log nnz) when sparse. Real-time safe.
  [[nodiscard]] double coeff(Eigen::Index i, Eigen::Index j) const noexcept;
  // Calls f(i, j, value) for every stored entry (every entry when dense). Not real-time safe.
  template <typename F>
  void for_each_entry(F&& f) const;

  // y = A x and y += s A x; sizes must match (asserted). Real-time safe: no allocation.
  // The diagonal and one-DOF arms are inline (below): for the few DOFs of a hybrid test's
  // model a call and its set-up cost more than the product. Dense and sparse products are
  // in the source file.
  void multiply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const noexcept {
    multiply_small<Eigen::Dynamic>(x, y);
  }
  void multiply_add(double s, const Eigen::Ref<const Eigen::VectorXd>& x,
                    Eigen::Ref<Eigen::VectorXd> y) const noexcept {
    multiply_add_small<Eigen::Dynamic>(s, x, y);
  }
  // The same products on whole vectors, without a Ref's set-up (its temporary costs a call to
  // free on every product); only for Eigen::VectorXd itself, so that nothing converts to one.
  // N, when given, is rows() known when the caller is compiled (a scheme's one-DOF step): the
  // same products, without the loops of run-time length.
  template <int N = Eigen::Dynamic, std::same_as<Eigen::VectorXd> X, std::same_as<Eigen::VectorXd> Y>
  void multiply(const X& x, Y& y) const noexcept {
    multiply_small<N>(x, y);
  }
  template <int N = Eigen::Dynamic, std::same_as<Eigen::VectorXd> X, std::same_as<Eigen::VectorXd> Y>
  void multiply_add(double s, const X& x, Y& y) const noexcept {
    multiply_add_small<N>(s, x, y);
  }

  // Largest |a_ij| (0 when empty); max |a_ij - a_ji| <= rel_tol * max_abs(); every entry
  // finite. Not real-time safe.
  [[nodiscard]] double max_abs() const;
  [[nodiscard]] bool is_symmetric(double rel_tol = 1e-10) const;
  [[nodiscard]] bool all_finite() const;

 private:
  MatrixStorage storage_ = MatrixStorage::kDense;
  Eigen::Index rows_ = 0, cols_ = 0;
  Eigen::VectorXd diagonal_;
  Eigen::MatrixXd dense_;
  SparseMatrix sparse_;
  // Row-major copy for products: y_i = row_i . x streams each row once instead of
  // scattering columns.
  Eigen::SparseMatrix<double, Eigen::RowMajor> sparse_rows_;
  std::vector<Eigen::Index> row_major_position_;  // of each stored value of sparse_

  template <int N, typename X, typename Y>
  void multiply_small(const X& x, Y& y) const noexcept;
  template <int N, typename X, typename Y>
  void multiply_add_small(double s, const X& x, Y& y) const noexcept;
  // rows() as the products loop over it: N when known at compile time.
  template <int N>
  Eigen::Index rows_of() const noexcept {
    assert(N == Eigen::Dynamic || N == rows_);
    if constexpr (N == Eigen::Dynamic) {
      return rows_;
    } else {
      return N;
    }
  }
  void multiply_stored(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const noexcept;
  void multiply_add_stored(double s, const Eigen::Ref<const Eigen::VectorXd>& x,
                           Eigen::Ref<Eigen::VectorXd> y) const noexcept;
};

template <int N, typename X, typename Y>
void StructuralMatrix::multiply_small(const X& x, Y& y) const noexcept {
  assert(x.size() == cols_ && y.size() == rows_);
  const Eigen::Index n = rows_of<N>();
  if (storage_ == MatrixStorage::kDiagonal) {
    // A plain loop: the same product per entry as Eigen's, without its set-up per call.
    const double* a = diagonal_.data();
    for (Eigen::Index i = 0; i < n; ++i) y[i] = a[i] * x[i];
  } else if (storage_ == MatrixStorage::kDense && n == 1) {
    // One DOF: Eigen's own path for a 1x1 product (an inner product added onto a zeroed y,
    // hence 0 + a x, which keeps its sign of zero), without the set-up of its general one.
    y[0] = 0.0 + dense_.data()[0] * x[0];
  } else {
    multiply_stored(x, y);
  }
}

template <int N, typename X, typename Y>
void StructuralMatrix::multiply_add_small(double s, const X& x, Y& y) const noexcept {
  assert(x.size() == cols_ && y.size() == rows_);
  if (storage_ == MatrixStorage::kDiagonal) {
    const double* a = diagonal_.data();  // (s a_i) x_i, as Eigen evaluates it
    const Eigen::Index n = rows_of<N>();
    for (Eigen::Index i = 0; i < n; ++i) y[i] += s * a[i] * x[i];
  } else {
    multiply_add_stored(s, x, y);
  }
}

template <typename F>
void StructuralMatrix::for_each_entry(F&& f) const {
  switch (storage_) {
    case MatrixStorage::kDiagonal:
      for (Eigen::Index i = 0; i < diagonal_.size(); ++i) f(i, i, diagonal_[i]);
      break;
    case MatrixStorage::kDense:
      for (Eigen::Index j = 0; j < dense_.cols(); ++j)
        for (Eigen::Index i = 0; i < dense_.rows(); ++i) f(i, j, dense_(i, j));
      break;
    case MatrixStorage::kSparse:
      for (Eigen::Index j = 0; j < sparse_.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(sparse_, j); it; ++it) f(it.row(), it.col(), it.value());
      break;
  }
}

}  // namespace rpsd::linalg
