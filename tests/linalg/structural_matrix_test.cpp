// The one structural matrix type: every storage gives the product of the matrix it holds
// (checked against Eigen's dense product), and storage is chosen and kept as documented.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "rpsd/linalg/structural_matrix.h"

namespace rpsd::linalg {
namespace {

Eigen::MatrixXd random_symmetric(int n, unsigned seed, double fill) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0), chance(0.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    a(j, j) = 2.0 + value(rng);
    for (int i = j + 1; i < n; ++i)
      if (chance(rng) < fill) a(i, j) = a(j, i) = value(rng);
  }
  return a;
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = value(rng);
  return x;
}

void expect_products_equal(const StructuralMatrix& m, const Eigen::MatrixXd& reference) {
  const auto n = static_cast<int>(reference.rows());
  const Eigen::VectorXd x = random_vector(n, 7);
  Eigen::VectorXd y(n);
  m.multiply(x, y);
  EXPECT_LT((y - reference * x).cwiseAbs().maxCoeff(), 1e-13);
  Eigen::VectorXd z = random_vector(n, 8);
  const Eigen::VectorXd z0 = z;
  m.multiply_add(-2.5, x, z);
  EXPECT_LT((z - (z0 - 2.5 * reference * x)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(StructuralMatrix, EveryStorageMultipliesLikeTheDenseMatrixItHolds) {
  const Eigen::MatrixXd a = random_symmetric(30, 1, 0.1);
  expect_products_equal(StructuralMatrix(a), a);
  expect_products_equal(StructuralMatrix(a).converted(MatrixStorage::kSparse), a);
  const Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(30, 1.0, 4.0);
  expect_products_equal(StructuralMatrix::diagonal(d), Eigen::MatrixXd(d.asDiagonal()));
}

TEST(StructuralMatrix, CompactingKeepsOnlyTheDiagonalOfADiagonalMatrix) {
  const Eigen::MatrixXd lumped = Eigen::VectorXd::LinSpaced(5, 1.0, 5.0).asDiagonal();
  const StructuralMatrix dense(lumped);
  EXPECT_EQ(dense.storage(), MatrixStorage::kDense);  // stored as given
  EXPECT_EQ(dense.compacted().storage(), MatrixStorage::kDiagonal);
  EXPECT_EQ(dense.compacted().diagonal_values(), lumped.diagonal());
  EXPECT_EQ(StructuralMatrix(dense.to_sparse()).compacted().storage(), MatrixStorage::kDiagonal);

  const Eigen::MatrixXd coupled = random_symmetric(5, 2, 1.0);
  EXPECT_EQ(StructuralMatrix(coupled).compacted().storage(), MatrixStorage::kDense);
  EXPECT_EQ(StructuralMatrix(coupled).converted(MatrixStorage::kSparse).compacted().storage(), MatrixStorage::kSparse);
  EXPECT_THROW((void)StructuralMatrix(coupled).converted(MatrixStorage::kDiagonal), std::invalid_argument);
}

TEST(StructuralMatrix, ALinearCombinationTakesTheMostGeneralStorage) {
  const Eigen::MatrixXd k = random_symmetric(6, 3, 0.5);
  const StructuralMatrix mass = StructuralMatrix::diagonal(Eigen::VectorXd::Constant(6, 2.0));
  const StructuralMatrix stiffness(k);
  const StructuralMatrix sum = StructuralMatrix::linear_combination(3.0, mass, 0.5, stiffness);
  EXPECT_EQ(sum.storage(), MatrixStorage::kDense);
  EXPECT_LT((sum.to_dense() - (6.0 * Eigen::MatrixXd::Identity(6, 6) + 0.5 * k)).cwiseAbs().maxCoeff(), 1e-15);
  const StructuralMatrix sparse =
      StructuralMatrix::linear_combination(1.0, mass, 1.0, stiffness, 2.0, stiffness.converted(MatrixStorage::kSparse));
  EXPECT_EQ(sparse.storage(), MatrixStorage::kSparse);
  EXPECT_LT((sparse.to_dense() - (2.0 * Eigen::MatrixXd::Identity(6, 6) + 3.0 * k)).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(StructuralMatrix::linear_combination(1.0, mass, 1.0, mass).storage(), MatrixStorage::kDiagonal);
  EXPECT_THROW(
      (void)StructuralMatrix::linear_combination(1.0, mass, 1.0, StructuralMatrix(Eigen::MatrixXd::Ones(2, 2))),
      std::invalid_argument);
}

TEST(StructuralMatrix, ProductsFollowValuesChangedInPlace) {
  // A tangent stiffness updated in place keeps its pattern; after values_changed() the
  // products use the new values.
  const Eigen::MatrixXd a = random_symmetric(12, 4, 0.3);
  StructuralMatrix m = StructuralMatrix(a).converted(MatrixStorage::kSparse);
  Eigen::MatrixXd changed = a;
  for (Eigen::Index j = 0; j < m.sparse_mut().outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(m.sparse_mut(), j); it; ++it) {
      it.valueRef() *= 1.0 + 0.1 * static_cast<double>(it.row() + 2 * it.col());
      changed(it.row(), it.col()) = it.value();
    }
  }
  m.values_changed();
  expect_products_equal(m, changed);
}

TEST(StructuralMatrix, ChecksSymmetryFinitenessAndSize) {
  Eigen::MatrixXd a = random_symmetric(4, 5, 1.0);
  EXPECT_TRUE(StructuralMatrix(a).is_symmetric());
  EXPECT_DOUBLE_EQ(StructuralMatrix(a).max_abs(), a.cwiseAbs().maxCoeff());
  a(0, 3) += 1e-3;
  EXPECT_FALSE(StructuralMatrix(a).is_symmetric());
  EXPECT_FALSE(StructuralMatrix(a).converted(MatrixStorage::kSparse).is_symmetric());
  a(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(StructuralMatrix(a).all_finite());
  EXPECT_FALSE(StructuralMatrix(a).converted(MatrixStorage::kSparse).all_finite());
  EXPECT_THROW((void)StructuralMatrix(a).sparse(), std::logic_error);
}

// The loop's products are plain loops for a diagonal or a 1x1 matrix (docs/performance.md):
// they must give Eigen's own digits, the sign of a zero included, or a test's records change.
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

TEST(StructuralMatrix, DiagonalAndOneByOneProductsGiveEigensDigits) {
  for (int n : {1, 2, 3, 5, 9}) {
    const Eigen::VectorXd d = random_vector(n, 11) * 1e5, x = random_vector(n, 12) / 3.0, z0 = random_vector(n, 13);
    const StructuralMatrix m = StructuralMatrix::diagonal(d);
    Eigen::VectorXd y(n), z = z0;
    m.multiply(x, y);
    m.multiply_add(-0.7, x, z);
    const Eigen::VectorXd y_eigen = (d.array() * x.array()).matrix();
    Eigen::VectorXd z_eigen = z0;
    z_eigen.array() += -0.7 * d.array() * x.array();
    for (int i = 0; i < n; ++i) {
      EXPECT_TRUE(same_bits(y[i], y_eigen[i])) << "n = " << n << ", entry " << i;
      EXPECT_TRUE(same_bits(z[i], z_eigen[i])) << "n = " << n << ", entry " << i;
    }
  }
  // 1x1 dense: Eigen adds the product onto a zeroed result, so -0 comes out as +0.
  for (const double k : {700.8e3, -3.0}) {
    const StructuralMatrix m(Eigen::MatrixXd::Constant(1, 1, k));
    for (const double value : {0.0, -0.0, 1.0 / 3.0, -2.5e-3}) {
      const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, value);
      Eigen::VectorXd y(1), y_eigen(1);
      m.multiply(x, y);
      y_eigen.noalias() = m.dense() * x;
      EXPECT_TRUE(same_bits(y[0], y_eigen[0])) << k << " x " << value << ": " << y[0] << " against " << y_eigen[0];
    }
  }
}

// The loop multiplies whole vectors through their own overloads (no Ref set-up); any other
// vector (a segment) goes through the Ref ones. Both must give the same digits, a zero's sign
// included, for every storage.
TEST(StructuralMatrix, WholeVectorsAndSegmentsGiveTheSameDigits) {
  const Eigen::MatrixXd a = random_symmetric(4, 3, 0.5);
  const std::vector<StructuralMatrix> matrices = {StructuralMatrix::diagonal(random_vector(4, 21)), StructuralMatrix(a),
                                                  StructuralMatrix(a).converted(MatrixStorage::kSparse),
                                                  StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, 3.0)),
                                                  StructuralMatrix::diagonal(random_vector(1, 24) * 7.3)};
  for (const StructuralMatrix& m : matrices)
    for (const bool negative_zero : {false, true}) {
      const Eigen::Index n = m.rows();
      Eigen::VectorXd x = random_vector(static_cast<int>(n), 22);
      if (negative_zero) x[0] = -0.0;
      const Eigen::VectorXd z0 = random_vector(static_cast<int>(n), 23);
      Eigen::VectorXd y(n), z = z0;
      m.multiply(x, y);
      m.multiply_add(-0.7, x, z);
      Eigen::VectorXd x_in(n + 2), y_in = Eigen::VectorXd::Zero(n + 2), z_in(n + 2);
      x_in.segment(1, n) = x;
      z_in.segment(1, n) = z0;
      m.multiply(x_in.segment(1, n), y_in.segment(1, n));
      m.multiply_add(-0.7, x_in.segment(1, n), z_in.segment(1, n));
      for (Eigen::Index i = 0; i < n; ++i) {
        EXPECT_TRUE(same_bits(y[i], y_in[i + 1])) << n << " DOFs, storage " << static_cast<int>(m.storage()) << ", "
                                                  << i << ": " << y[i] << " against " << y_in[i + 1];
        EXPECT_TRUE(same_bits(z[i], z_in[i + 1])) << n << " DOFs, storage " << static_cast<int>(m.storage()) << ", "
                                                  << i << ": " << z[i] << " against " << z_in[i + 1];
      }
    }
}

}  // namespace
}  // namespace rpsd::linalg
