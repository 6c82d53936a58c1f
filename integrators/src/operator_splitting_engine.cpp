#include "rpsd/integrators/operator_splitting_engine.h"

namespace rpsd::integrators {

void OperatorSplittingEngine::on_configure() {
  const double s = 1.0 + c_.alpha;
  const linalg::StructuralMatrix m_hat =
      linalg::StructuralMatrix::linear_combination(1.0, mass_, s * c_.gamma * dt_s_, damping_,
                                                   s * c_.beta * dt_s_ * dt_s_, stiffness_)
          .compacted();
  effective_mass_solver_.factorize(m_hat,
                                   "effective mass matrix M + (1+alpha) gamma dt C + "
                                   "(1+alpha) beta dt^2 K0");
  for (auto* v : {&v_pred_, &r_meas_, &rhs_, &a_next_}) v->setZero(n_);
}

void OperatorSplittingEngine::on_begin_step() {
  const double dt = dt_s_;
  command_ = d_ + dt * v_ + (dt * dt * (0.5 - c_.beta)) * a_;
  v_pred_ = v_ + (dt * (1.0 - c_.gamma)) * a_;
}

void OperatorSplittingEngine::on_restoring_force(int /*iteration*/, const Eigen::VectorXd& r) { r_meas_ = r; }

void OperatorSplittingEngine::on_end_step() {
  const double a = c_.alpha;
  const double s = 1.0 + a;
  const double dt = dt_s_;
  rhs_ = s * f_next_ - a * f_ - s * r_meas_ + a * r_;
  damping_.multiply_add(-s, v_pred_, rhs_);
  if (a != 0.0) damping_.multiply_add(a, v_, rhs_);
  effective_mass_solver_.solve(rhs_, a_next_);

  const double bdt2 = c_.beta * dt * dt;
  d_ = command_ + bdt2 * a_next_;
  v_ = v_pred_ + (c_.gamma * dt) * a_next_;
  r_ = r_meas_;
  if (bdt2 != 0.0) stiffness_.multiply_add(bdt2, a_next_, r_);
  a_.swap(a_next_);
}

}  // namespace rpsd::integrators
