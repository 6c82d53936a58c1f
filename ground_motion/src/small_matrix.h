// Exponential of a small dense matrix by scaling and squaring with a Taylor series, in
// plain loops (a fixed order of operations, so the result does not depend on SIMD width).
// Used for exact discretisations: zero-order hold (synthetic filters) and first-order hold
// (piecewise-linear SDOF). Internal.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace rpsd::ground_motion::detail {

template <std::size_t N>
using SquareMatrix = std::array<std::array<double, N>, N>;

template <std::size_t N>
SquareMatrix<N> multiply(const SquareMatrix<N>& a, const SquareMatrix<N>& b) {
  SquareMatrix<N> c{};
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = 0; j < N; ++j) {
      double sum = 0.0;
      for (std::size_t k = 0; k < N; ++k) sum += a[i][k] * b[k][j];
      c[i][j] = sum;
    }
  }
  return c;
}

// e^M. The matrix is scaled by 2^-s until its infinity norm is at most 1/2, where the
// Taylor series to degree 18 leaves a remainder below 1e-22; then squared s times.
template <std::size_t N>
SquareMatrix<N> matrix_exponential(SquareMatrix<N> m) {
  double norm = 0.0;
  for (const auto& row : m) {
    double sum = 0.0;
    for (double v : row) sum += std::abs(v);
    norm = std::max(norm, sum);
  }
  int squarings = 0;
  if (norm > 0.5) {
    std::frexp(norm / 0.5, &squarings);  // norm / 0.5 < 2^squarings
    const double factor = std::ldexp(1.0, -squarings);
    for (auto& row : m) {
      for (double& v : row) v *= factor;
    }
  }
  // Horner: I + M (I + M/2 (I + M/3 (... (I + M/18))))
  constexpr int degree = 18;
  SquareMatrix<N> result{};
  for (std::size_t i = 0; i < N; ++i) result[i][i] = 1.0;
  for (int k = degree; k >= 1; --k) {
    SquareMatrix<N> term = multiply(m, result);
    for (std::size_t i = 0; i < N; ++i) {
      for (std::size_t j = 0; j < N; ++j) {
        result[i][j] = (i == j ? 1.0 : 0.0) + term[i][j] / static_cast<double>(k);
      }
    }
  }
  for (int s = 0; s < squarings; ++s) result = multiply(result, result);
  return result;
}

}  // namespace rpsd::ground_motion::detail
