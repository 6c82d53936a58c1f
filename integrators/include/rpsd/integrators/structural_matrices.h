#pragma once
// The linear part of M a + C v + R(d) = F that a scheme needs: mass, damping and the
// initial stiffness K0 (used by implicit iterations and by the model-based explicit
// schemes). The restoring force R itself is measured or computed outside the integrator.
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <variant>

namespace rpsd::integrators {

/// Small models: dense matrices. SI units: kg, N s/m, N/m.
struct DenseStructuralMatrices {
  Eigen::MatrixXd mass_kg;
  Eigen::MatrixXd damping_N_s_per_m;
  Eigen::MatrixXd initial_stiffness_N_per_m;
};

/// Large models: sparse matrices (both triangles stored).
struct SparseStructuralMatrices {
  Eigen::SparseMatrix<double> mass_kg;
  Eigen::SparseMatrix<double> damping_N_s_per_m;
  Eigen::SparseMatrix<double> initial_stiffness_N_per_m;
};

using StructuralMatrices = std::variant<DenseStructuralMatrices, SparseStructuralMatrices>;

}  // namespace rpsd::integrators
