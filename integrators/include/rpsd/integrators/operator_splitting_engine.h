#pragma once
// Shared machinery of the Newmark predictor-corrector schemes that are explicit in
// displacement: central difference (alpha = 0, beta = 0, gamma = 1/2) and alpha-OS
// (operator splitting with the initial stiffness K_I = K0).
//   predictor  x~ = x + dt v + dt^2 (1/2 - beta) a      <- the command
//              v~ = v + dt (1 - gamma) a
//   corrector  [M + (1+alpha) gamma dt C + (1+alpha) beta dt^2 K_I] a+ =
//              (1+alpha) F+ - alpha F - (1+alpha)(C v~ + R~+) + alpha (C v + R)
//              x+ = x~ + beta dt^2 a+,  v+ = v~ + gamma dt a+,  R+ = R~+ + beta dt^2 K_I a+
#include "rpsd/integrators/integrator.h"

namespace rpsd::integrators {

struct OperatorSplittingCoefficients {
  double alpha = 0.0;
  double beta = 0.0;
  double gamma = 0.5;
};

class OperatorSplittingEngine : public Integrator {
 protected:
  explicit OperatorSplittingEngine(const OperatorSplittingCoefficients& c) : c_(c) {}

  void on_configure() override;
  void on_set_state() override {}
  void on_begin_step() override;
  void on_restoring_force(int iteration, const Eigen::VectorXd& r) override;
  void on_end_step() override;

 private:
  // The per-step arithmetic once, over the DOFs as a compile-time N (1: a one-DOF model, whose
  // loops and products the compiler makes scalar) or Eigen::Dynamic; configure picks which.
  template <int N>
  void begin_step_of();
  template <int N>
  void restoring_force_of(const Eigen::VectorXd& r);
  template <int N>
  void end_step_of();
  template <int N>
  static void take(Eigen::VectorXd& to, Eigen::VectorXd& from) noexcept;

  OperatorSplittingCoefficients c_;
  SymmetricSolver effective_mass_solver_;
  Eigen::VectorXd v_pred_, r_meas_, rhs_, a_next_;
  bool one_dof_ = false;
};

}  // namespace rpsd::integrators
