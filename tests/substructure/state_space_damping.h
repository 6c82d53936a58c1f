// Damping ratios of M a + C v + K d = 0 from the eigenvalues of its state matrix
// [0 I; -M^-1 K, -M^-1 C]: each mode's pair lambda = -zeta w +/- j w sqrt(1 - zeta^2), so
// zeta = -Re(lambda) / |lambda|, in ascending |lambda|. Independent of how C was built (it
// needs no mode shapes and no proportional damping).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <vector>

namespace rpsd::substructure::test {

inline std::vector<double> state_space_damping_ratios(const Eigen::MatrixXd& m, const Eigen::MatrixXd& c,
                                                      const Eigen::MatrixXd& k) {
  const Eigen::Index n = m.rows();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  const Eigen::MatrixXd m_inv = m.inverse();
  a.topRightCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
  a.bottomLeftCorner(n, n) = -m_inv * k;
  a.bottomRightCorner(n, n) = -m_inv * c;
  const Eigen::VectorXcd lambda = a.eigenvalues();
  std::vector<std::pair<double, double>> modes;  // |lambda|, zeta: one per pair (Im > 0)
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (lambda[i].imag() > 0.0) modes.emplace_back(std::abs(lambda[i]), -lambda[i].real() / std::abs(lambda[i]));
  }
  std::sort(modes.begin(), modes.end());
  std::vector<double> zeta;
  for (const auto& [w, z] : modes) zeta.push_back(z);
  return zeta;
}

}  // namespace rpsd::substructure::test
