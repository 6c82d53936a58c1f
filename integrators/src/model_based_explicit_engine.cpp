#include "rpsd/integrators/model_based_explicit_engine.h"

namespace rpsd::integrators {

void ModelBasedExplicitEngine::on_configure() {
  const double dt = dt_s_;
  const double gdt = c_.gamma * dt;
  const double bdt2 = c_.beta * dt * dt;
  d_matrix_ = linalg::StructuralMatrix::linear_combination(1.0, mass_, gdt, damping_, bdt2, stiffness_).compacted();
  d_solver_.factorize(d_matrix_, "model-based matrix D = M + gamma dt C + beta dt^2 K0");
  const double sf = 1.0 - c_.alpha_f;
  const linalg::StructuralMatrix e =
      linalg::StructuralMatrix::linear_combination(1.0 - c_.alpha_m, mass_, sf * gdt, damping_, sf * bdt2, stiffness_)
          .compacted();
  e_solver_.factorize(e,
                      "equilibrium matrix (1-alpha_m) M + (1-alpha_f)(gamma dt C + "
                      "beta dt^2 K0)");
  for (auto* v : {&w_, &ma_, &v_next_, &r_meas_, &rhs_, &tmp_, &w_next_}) v->setZero(n_);
}

void ModelBasedExplicitEngine::on_set_state() {
  mass_.multiply(a_, ma_);
  d_solver_.solve(ma_, w_);
}

void ModelBasedExplicitEngine::on_begin_step() {
  const double dt = dt_s_;
  v_next_ = v_ + dt * w_;
  command_ = d_ + dt * v_ + (dt * dt * (0.5 + c_.gamma)) * w_;
}

void ModelBasedExplicitEngine::on_restoring_force(int /*iteration*/, const Eigen::VectorXd& r) { r_meas_ = r; }

void ModelBasedExplicitEngine::on_end_step() {
  const double af = c_.alpha_f;
  const double sf = 1.0 - af;
  // v~ = (1-af) v+ + af v, in tmp_
  tmp_ = sf * v_next_ + af * v_;
  rhs_ = sf * (f_next_ - r_meas_) + af * (f_ - r_) - af * ma_;
  damping_.multiply_add(-1.0, tmp_, rhs_);
  if (c_.alpha_m != af) mass_.multiply_add(-(c_.alpha_m - af), w_, rhs_);
  e_solver_.solve(rhs_, w_next_);

  d_matrix_.multiply(w_next_, ma_);  // M a+ = D w+
  mass_solver_.solve(ma_, a_);
  d_.swap(command_);
  v_.swap(v_next_);
  w_.swap(w_next_);
  r_ = r_meas_;
  command_ = d_;
}

}  // namespace rpsd::integrators
