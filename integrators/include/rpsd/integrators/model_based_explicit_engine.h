#pragma once
// Shared machinery of the model-based explicit schemes (explicit in displacement and
// velocity, integration parameters built from M, C, K0): CR (Chen-Ricles; alpha_m =
// alpha_f = 0, gamma = 1/2, beta = 1/4) and KR-alpha (Kolay-Ricles).
//   D = M + gamma dt C + beta dt^2 K0, alpha1 = D^-1 M, alpha2 = (1/2 + gamma) alpha1,
//   alpha3 = D^-1 (alpha_m M + alpha_f (gamma dt C + beta dt^2 K0))
//   v+ = v + dt alpha1 a,  x+ = x + dt v + dt^2 alpha2 a      <- the command
//   M[(I - alpha3) a+ + alpha3 a] + C v_{n+1-af} + R_{n+1-af} = F_{n+1-af}
// alpha1..3 are dense even for sparse models, so they are never formed. The scheme
// carries w = alpha1 a instead: since alpha3 = alpha_f I + (alpha_m - alpha_f) alpha1 and
// M a+ = D w+, the equilibrium becomes one symmetric solve per step,
//   [(1 - alpha_m) M + (1 - alpha_f)(gamma dt C + beta dt^2 K0)] w+ =
//       F~ - C v~ - R~ - alpha_f M a - (alpha_m - alpha_f) M w,
// followed by M a+ = D w+ (a solve with M, trivial for a lumped mass).
#include "rpsd/integrators/integrator.h"

namespace rpsd::integrators {

struct ModelBasedCoefficients {
  double alpha_m = 0.0;
  double alpha_f = 0.0;
  double gamma = 0.5;
  double beta = 0.25;
};

class ModelBasedExplicitEngine : public Integrator {
 protected:
  explicit ModelBasedExplicitEngine(const ModelBasedCoefficients& c) : c_(c) {}

  void on_configure() override;
  void on_set_state() override;
  void on_begin_step() override;
  void on_restoring_force(int iteration, const Eigen::VectorXd& r) override;
  void on_end_step() override;

 private:
  ModelBasedCoefficients c_;
  linalg::StructuralMatrix d_matrix_;  // D = M + gamma dt C + beta dt^2 K0
  SymmetricSolver d_solver_;           // only to derive w from a in set_state()
  SymmetricSolver e_solver_;           // E = (1-am) M + (1-af)(gamma dt C + beta dt^2 K0)
  Eigen::VectorXd w_, ma_, v_next_, r_meas_, rhs_, tmp_, w_next_;
};

}  // namespace rpsd::integrators
