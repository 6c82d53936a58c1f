#pragma once
// Shared machinery of the implicit Newmark-family schemes run with a fixed number of
// iterations per step, as hybrid tests need (cf. OpenSees NewmarkHSFixedNumIter /
// HHTHSFixedNumIter): Newmark (alpha_m = alpha_f = 0), HHT-alpha (alpha_m = 0,
// alpha_f = -alpha) and generalized-alpha. Equilibrium at t + dt - alpha_f:
//   (1-am) M a+ + am M a + (1-af)(C v+ + R(x+)) + af (C v + R) = (1-af) F+ + af F
// with Newmark a+(x+), v+(x+). Each iteration solves with the constant matrix
//   K^ = (1-am)/(beta dt^2) M + (1-af) gamma/(beta dt) C + (1-af) K0
// and, instead of jumping to the Newton update U + dU, commands the Lagrange polynomial
// through U_{t-p+1}, ..., U_t (at x = -p+1..0) and U + dU (at x = 1) evaluated at
// x = i/N. For order 1: U_i = x (U + dU) + (1 - x) U_t. The last command (x = 1) is the
// full Newton update, so every command is one an actuator can follow.
#include "rpsd/integrators/integrator.h"

#include <string>
#include <vector>

namespace rpsd::integrators {

// How many commands per step and the interpolation order (1, 2 or 3).
struct FixedIterationOptions {
  int iterations = 2;
  int poly_order = 1;
};
// " iterations=2 poly_order=1", the end of a scheme's describe().
std::string describe(const FixedIterationOptions& options);

struct ImplicitCoefficients {
  double alpha_m = 0.0;
  double alpha_f = 0.0;
  double beta = 0.25;
  double gamma = 0.5;
};

// Throws std::invalid_argument unless 1 <= iterations <= 100 and poly_order in {1, 2, 3}.
void validate(const FixedIterationOptions& options);

class FixedIterationImplicitEngine : public Integrator {
 protected:
  FixedIterationImplicitEngine(const ImplicitCoefficients& c, const FixedIterationOptions& o);

  void on_configure() override;
  void on_set_state() override;
  void on_begin_step() override;
  void on_restoring_force(int iteration, const Eigen::VectorXd& r) override;
  void on_end_step() override;

 private:
  // command_ = interpolated command of iteration `i` (1-based) towards `target`.
  void interpolate(int i, const Eigen::VectorXd& target);
  // Residual at the current command with restoring force r, then command of iteration i.
  void iterate(int i, const Eigen::VectorXd& r);

  ImplicitCoefficients c_;
  FixedIterationOptions o_;
  linalg::StructuralMatrix k_dynamic_;  // K^ - (1-af) K0
  SymmetricSolver k_hat_solver_;
  std::vector<double> weights_;           // [(i-1)*(p+1) + j], node j at x = j - p + 1
  std::vector<Eigen::VectorXd> history_;  // U_{t-1}, U_{t-2} (poly order 2, 3)
  Eigen::VectorXd a_pred_, v_pred_, r_const_, residual_, delta_, target_, tmp_, r_meas_;
};

}  // namespace rpsd::integrators
