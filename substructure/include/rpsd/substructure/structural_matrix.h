#pragma once
// A square structural matrix (mass, damping, stiffness) stored dense for small models and
// sparse (compressed column) for large ones, behind one type so that models and schemes
// can take either.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <variant>

namespace rpsd::substructure {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, compressed after construction

enum class MatrixStorage { dense, sparse };

class StructuralMatrix {
 public:
  StructuralMatrix() = default;
  // Not real-time safe (takes ownership by move; a sparse matrix is compressed).
  explicit StructuralMatrix(Eigen::MatrixXd dense);
  explicit StructuralMatrix(SparseMatrix sparse);

  [[nodiscard]] bool is_sparse() const noexcept {
    return std::holds_alternative<SparseMatrix>(storage_);
  }
  [[nodiscard]] MatrixStorage storage() const noexcept {
    return is_sparse() ? MatrixStorage::sparse : MatrixStorage::dense;
  }
  [[nodiscard]] Eigen::Index rows() const noexcept;
  [[nodiscard]] Eigen::Index cols() const noexcept;

  // The stored representation. Throws std::logic_error when asked for the other one.
  [[nodiscard]] const Eigen::MatrixXd& dense() const;
  [[nodiscard]] const SparseMatrix& sparse() const;
  // Mutable access for in-place value updates that keep the sparsity pattern.
  [[nodiscard]] Eigen::MatrixXd& dense_mut();
  [[nodiscard]] SparseMatrix& sparse_mut();

  // Copies in the other representation. Not real-time safe.
  [[nodiscard]] Eigen::MatrixXd to_dense() const;
  [[nodiscard]] SparseMatrix to_sparse() const;
  // Same matrix in the requested storage. Not real-time safe.
  [[nodiscard]] StructuralMatrix converted(MatrixStorage storage) const;

  // Entry (i, j); O(log nnz) for sparse. Real-time safe.
  [[nodiscard]] double coeff(Eigen::Index i, Eigen::Index j) const noexcept;

  // y = A x. Sizes must match (asserted). Real-time safe: no allocation.
  void multiply(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> y) const noexcept;
  // y += s A x. Real-time safe.
  void multiply_add(const Eigen::Ref<const Eigen::VectorXd>& x, double s,
                    Eigen::Ref<Eigen::VectorXd> y) const noexcept;

  // a A + b B with the storage of A (sparse if either is sparse). Not real-time safe.
  [[nodiscard]] static StructuralMatrix linear_combination(double a, const StructuralMatrix& A,
                                                           double b, const StructuralMatrix& B);

 private:
  std::variant<Eigen::MatrixXd, SparseMatrix> storage_{Eigen::MatrixXd{}};
};

}  // namespace rpsd::substructure
