#include "rpsd/servo/polynomial.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

namespace rpsd::servo {

Polynomial::Polynomial(std::initializer_list<double> ascending)
    : coefficients_(Eigen::VectorXd::Map(ascending.begin(), static_cast<Eigen::Index>(ascending.size()))) {
  if (coefficients_.size() == 0) coefficients_ = Eigen::VectorXd::Zero(1);
  trim();
}

Polynomial::Polynomial(Eigen::VectorXd ascending) : coefficients_(std::move(ascending)) {
  if (coefficients_.size() == 0) coefficients_ = Eigen::VectorXd::Zero(1);
  trim();
}

void Polynomial::trim() {
  Eigen::Index n = coefficients_.size();
  while (n > 1 && coefficients_[n - 1] == 0.0) --n;
  coefficients_.conservativeResize(n);
}

int Polynomial::degree() const { return static_cast<int>(coefficients_.size()) - 1; }

double Polynomial::coefficient(int power) const {
  return power >= 0 && power < coefficients_.size() ? coefficients_[power] : 0.0;
}

std::complex<double> Polynomial::operator()(std::complex<double> s) const {
  std::complex<double> value = 0.0;
  for (Eigen::Index i = coefficients_.size() - 1; i >= 0; --i) value = value * s + coefficients_[i];
  return value;
}

Polynomial Polynomial::operator+(const Polynomial& other) const {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(std::max(coefficients_.size(), other.coefficients_.size()));
  sum.head(coefficients_.size()) += coefficients_;
  sum.head(other.coefficients_.size()) += other.coefficients_;
  return Polynomial(sum);
}

Polynomial Polynomial::operator*(const Polynomial& other) const {
  Eigen::VectorXd product = Eigen::VectorXd::Zero(coefficients_.size() + other.coefficients_.size() - 1);
  for (Eigen::Index i = 0; i < coefficients_.size(); ++i)
    for (Eigen::Index j = 0; j < other.coefficients_.size(); ++j)
      product[i + j] += coefficients_[i] * other.coefficients_[j];
  return Polynomial(product);
}

Polynomial Polynomial::operator*(double factor) const { return Polynomial(Eigen::VectorXd(coefficients_ * factor)); }

Eigen::VectorXcd Polynomial::roots() const {
  const int n = degree();
  if (n < 1) return {};
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n, n);
  companion.bottomLeftCorner(n - 1, n - 1).setIdentity();
  companion.col(n - 1) = -coefficients_.head(n) / coefficients_[n];
  return balanced_eigenvalues(companion);
}

Eigen::VectorXcd balanced_eigenvalues(Eigen::MatrixXd a) {
  constexpr double kRadix = 2.0;
  const Eigen::Index n = a.rows();
  bool converged = false;
  while (!converged) {
    converged = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      double column = 0.0, row = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (j == i) continue;
        column += std::abs(a(j, i));
        row += std::abs(a(i, j));
      }
      if (column == 0.0 || row == 0.0) continue;
      const double sum = column + row;
      double factor = 1.0;
      for (double g = row / kRadix; column < g; column *= kRadix * kRadix) factor *= kRadix;
      for (double g = row * kRadix; column > g; column /= kRadix * kRadix) factor /= kRadix;
      if ((column + row) / factor < 0.95 * sum) {
        converged = false;
        a.row(i) /= factor;
        a.col(i) *= factor;
      }
    }
  }
  return Eigen::EigenSolver<Eigen::MatrixXd>(a, false).eigenvalues();
}

std::complex<double> TransferFunction::at_frequency_hz(double frequency_hz) const {
  return (*this)(std::complex<double>(0.0, 2.0 * std::numbers::pi * frequency_hz));
}

}  // namespace rpsd::servo
