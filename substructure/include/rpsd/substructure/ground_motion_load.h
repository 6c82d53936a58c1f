#pragma once
// Effective earthquake load F(t) = −M ι a_g(t).

#include "rpsd/linalg/structural_matrix.h"

#include <Eigen/Core>

namespace rpsd::substructure {

class GroundMotionLoad {
 public:
  // Precomputes M ι. Throws std::invalid_argument if sizes differ or ι is not finite.
  // Not real-time safe.
  void configure(const linalg::StructuralMatrix& mass, const Eigen::VectorXd& influence);

  // force = −M ι · ground_acceleration. Real-time safe.
  // A plain loop: the same product per entry as Eigen's, without its set-up per call.
  void force(double ground_acceleration_m_s2, Eigen::Ref<Eigen::VectorXd> out) const noexcept {
    const double a = -ground_acceleration_m_s2;
    const double* m = m_iota_.data();
    for (Eigen::Index i = 0; i < m_iota_.size(); ++i) out[i] = a * m[i];
  }
  [[nodiscard]] const Eigen::VectorXd& mass_times_influence() const noexcept { return m_iota_; }

 private:
  Eigen::VectorXd m_iota_;
};

}  // namespace rpsd::substructure
