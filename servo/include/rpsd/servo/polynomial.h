// Real polynomials in s with coefficients in ascending powers (c0 + c1 s + c2 s^2 ...),
// and rational transfer functions built from them. Not real-time safe (they allocate).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <initializer_list>

namespace rpsd::servo {

class Polynomial {
 public:
  Polynomial() : coefficients_(Eigen::VectorXd::Zero(1)) {}
  // Coefficients in ascending powers: {c0, c1, c2} is c0 + c1 s + c2 s^2.
  Polynomial(std::initializer_list<double> ascending);
  explicit Polynomial(Eigen::VectorXd ascending);

  int degree() const;
  double coefficient(int power) const;
  const Eigen::VectorXd& coefficients() const { return coefficients_; }

  std::complex<double> operator()(std::complex<double> s) const;
  Polynomial operator+(const Polynomial& other) const;
  Polynomial operator*(const Polynomial& other) const;
  Polynomial operator*(double factor) const;

  // All roots, from the eigenvalues of the companion matrix.
  Eigen::VectorXcd roots() const;

 private:
  void trim();
  Eigen::VectorXd coefficients_;
};

// Eigenvalues of a general real matrix after diagonal balancing (Parlett-Reinsch, powers
// of two). Hydraulic models mix entries from 1e-16 to 1e10; without balancing the QR
// iteration loses several digits.
Eigen::VectorXcd balanced_eigenvalues(Eigen::MatrixXd matrix);

// G(s) = numerator(s) / denominator(s).
struct TransferFunction {
  Polynomial numerator;
  Polynomial denominator;

  std::complex<double> operator()(std::complex<double> s) const { return numerator(s) / denominator(s); }
  std::complex<double> at_frequency_hz(double frequency_hz) const;
  double static_gain() const { return numerator.coefficient(0) / denominator.coefficient(0); }
};

}  // namespace rpsd::servo
