#pragma once
// A symmetric structural matrix stored the cheapest way that represents it exactly:
// diagonal (lumped mass, no damping), dense (small models) or sparse (large models).
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <string_view>

namespace rpsd::integrators {

enum class Storage { diagonal, dense, sparse };

class SystemMatrix {
 public:
  SystemMatrix() = default;
  /// Not real-time safe. Detects a diagonal matrix and stores only its diagonal.
  static SystemMatrix from_dense(const Eigen::MatrixXd& a);
  /// Not real-time safe. Detects a diagonal matrix and stores only its diagonal.
  static SystemMatrix from_sparse(const Eigen::SparseMatrix<double>& a);
  /// Not real-time safe. a*A + b*B + c*C in the most general storage of the three.
  static SystemMatrix combine(double a, const SystemMatrix& A, double b, const SystemMatrix& B,
                              double c, const SystemMatrix& C);

  Eigen::Index rows() const { return rows_; }
  Eigen::Index cols() const { return cols_; }
  Storage storage() const { return storage_; }

  /// y = A x. Real-time safe (no allocation); y must already have the right size.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// y += s A x. Real-time safe.
  void multiply_add(double s, const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  /// Largest |a_ij|; 0 for an empty or zero matrix. Not real-time safe.
  double max_abs() const;
  /// max |a_ij - a_ji| <= rel_tol * max_abs(). Not real-time safe.
  bool is_symmetric(double rel_tol = 1e-10) const;
  bool all_finite() const;
  Eigen::MatrixXd to_dense() const;
  Eigen::SparseMatrix<double> to_sparse() const;

  const Eigen::VectorXd& diagonal_values() const { return diag_; }
  const Eigen::MatrixXd& dense() const { return dense_; }
  const Eigen::SparseMatrix<double>& sparse() const { return sparse_; }

 private:
  Storage storage_ = Storage::diagonal;
  Eigen::Index rows_ = 0;
  Eigen::Index cols_ = 0;
  Eigen::VectorXd diag_;
  Eigen::MatrixXd dense_;
  Eigen::SparseMatrix<double> sparse_;
  // Row-major copy for products: y_i = row_i . x streams each row once (dot products)
  // instead of scattering columns, about twice as fast for banded models.
  Eigen::SparseMatrix<double, Eigen::RowMajor> sparse_rows_;
};

}  // namespace rpsd::integrators
