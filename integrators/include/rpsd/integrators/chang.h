#pragma once
// Chang's explicit unconditionally stable method (Chang, J. Eng. Mech. 128(9), 2002):
//   B = M + dt/2 C + dt^2/4 K0,  beta1 = B^-1 (M + dt/2 C),  beta2 = 1/2 B^-1 M
//   x+ = x + beta1 dt v + beta2 dt^2 a                       <- the command
//   (M + dt/2 C) a+ = F+ - R(x+) - C (v + dt/2 a),  v+ = v + dt/2 (a + a+)
// Its eigenvalues equal those of average acceleration on linear systems.
#include <string>

#include "rpsd/integrators/integrator.h"
#include "rpsd/integrators/integrator_kind.h"

namespace rpsd::integrators {

class Chang;

struct ChangParameters {
  static constexpr std::string_view kName = "chang";
  static constexpr std::string_view kSummary = "Chang's explicit unconditionally stable method";
  using Integrator = Chang;
  static ChangParameters read(config::Source&) { return {}; }
  std::string describe() const { return "(none)"; }
};
using ChangParams [[deprecated("renamed ChangParameters (docs/migration.md)")]] = ChangParameters;

class Chang final : public Integrator {
 public:
  explicit Chang(const ChangParameters& = {}) {}
  SchemeInfo info() const override;

 private:
  void on_configure() override;
  void on_set_state() override;
  void on_begin_step() override;
  void on_restoring_force(int iteration, const Eigen::VectorXd& r) override;
  void on_end_step() override;

  linalg::StructuralMatrix p_matrix_;  // M + dt/2 C
  SymmetricSolver b_solver_, p_solver_;
  Eigen::VectorXd ma_, rhs_, tmp_, r_meas_, a_next_;
};

}  // namespace rpsd::integrators
