#include "rpsd/integrators/chang.h"

#include <limits>

namespace rpsd::integrators {

SchemeInfo Chang::info() const { return {ChangParameters::kName, true, std::numeric_limits<double>::infinity()}; }

void Chang::on_configure() {
  const double dt = dt_s_;
  const linalg::StructuralMatrix b =
      linalg::StructuralMatrix::linear_combination(1.0, mass_, 0.5 * dt, damping_, 0.25 * dt * dt, stiffness_)
          .compacted();
  b_solver_.factorize(b, "Chang matrix B = M + dt/2 C + dt^2/4 K0");
  p_matrix_ = linalg::StructuralMatrix::linear_combination(1.0, mass_, 0.5 * dt, damping_, 0.0, stiffness_).compacted();
  p_solver_.factorize(p_matrix_, "matrix M + dt/2 C");
  for (auto* v : {&ma_, &rhs_, &tmp_, &r_meas_, &a_next_}) v->setZero(n_);
}

void Chang::on_set_state() { mass_.multiply(a_, ma_); }

void Chang::on_begin_step() {
  const double dt = dt_s_;
  // x+ - x = B^-1 [(M + dt/2 C) dt v + dt^2/2 M a]
  p_matrix_.multiply(v_, rhs_);
  rhs_ = dt * rhs_ + (0.5 * dt * dt) * ma_;
  b_solver_.solve(rhs_, tmp_);
  command_ = d_ + tmp_;
}

void Chang::on_restoring_force(int /*iteration*/, const Eigen::VectorXd& r) { r_meas_ = r; }

void Chang::on_end_step() {
  const double dt = dt_s_;
  rhs_ = f_next_ - r_meas_;
  tmp_ = v_ + (0.5 * dt) * a_;
  damping_.multiply_add(-1.0, tmp_, rhs_);
  p_solver_.solve(rhs_, a_next_);
  v_ += (0.5 * dt) * (a_ + a_next_);
  a_.swap(a_next_);
  d_ = command_;
  r_ = r_meas_;
  mass_.multiply(a_, ma_);
}

}  // namespace rpsd::integrators
