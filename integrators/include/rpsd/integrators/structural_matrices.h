// The linear part of M a + C v + R(d) = F that a scheme needs: mass, damping and the
// initial stiffness K0 (used by implicit iterations and by the model-based explicit
// schemes). The restoring force R itself is measured or computed outside the integrator.
#pragma once

#include <Eigen/Core>

#include "rpsd/linalg/structural_matrix.h"

namespace rpsd::integrators {

struct StructuralMatrices {
  linalg::StructuralMatrix mass_kg;
  linalg::StructuralMatrix damping_n_s_per_m;
  linalg::StructuralMatrix initial_stiffness_n_per_m;

  // Not real-time safe.
  static StructuralMatrices dense(const Eigen::MatrixXd& mass_kg, const Eigen::MatrixXd& damping_n_s_per_m,
                                  const Eigen::MatrixXd& initial_stiffness_n_per_m) {
    return {linalg::StructuralMatrix(mass_kg), linalg::StructuralMatrix(damping_n_s_per_m),
            linalg::StructuralMatrix(initial_stiffness_n_per_m)};
  }
  static StructuralMatrices sparse(const linalg::SparseMatrix& mass_kg, const linalg::SparseMatrix& damping_n_s_per_m,
                                   const linalg::SparseMatrix& initial_stiffness_n_per_m) {
    return {linalg::StructuralMatrix(mass_kg), linalg::StructuralMatrix(damping_n_s_per_m),
            linalg::StructuralMatrix(initial_stiffness_n_per_m)};
  }
};

}  // namespace rpsd::integrators
