#include "rpsd/servo/harmonic_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace rpsd::servo {

HarmonicFit fit_harmonic(std::span<const double> reference_phase_rad, std::span<const double> signal) {
  if (reference_phase_rad.size() != signal.size() || signal.size() < 3) {
    throw std::invalid_argument("fit_harmonic: need at least 3 samples and equal lengths");
  }
  const auto n = static_cast<Eigen::Index>(signal.size());
  Eigen::MatrixXd basis(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    basis(i, 0) = std::sin(reference_phase_rad[i]);
    basis(i, 1) = std::cos(reference_phase_rad[i]);
    basis(i, 2) = 1.0;
  }
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(signal.data(), n);
  const Eigen::Vector3d coefficients = basis.colPivHouseholderQr().solve(y);
  return {std::hypot(coefficients[0], coefficients[1]), std::atan2(coefficients[1], coefficients[0])};
}

}  // namespace rpsd::servo
