#include "rpsd/integrators/fixed_iteration_implicit_engine.h"

#include <sstream>

#include <stdexcept>
#include <string>

namespace rpsd::integrators {

std::string describe(const FixedIterationOptions& options) {
  std::ostringstream s;
  s << " iterations=" << options.iterations << " poly_order=" << options.poly_order;
  return s.str();
}

void validate(const FixedIterationOptions& o) {
  if (o.iterations < 1 || o.iterations > 100)
    throw std::invalid_argument("fixed_iteration.iterations must be in [1, 100], got " + std::to_string(o.iterations));
  if (o.poly_order < 1 || o.poly_order > 3)
    throw std::invalid_argument("fixed_iteration.poly_order must be 1, 2 or 3, got " + std::to_string(o.poly_order));
}

FixedIterationImplicitEngine::FixedIterationImplicitEngine(const ImplicitCoefficients& c,
                                                           const FixedIterationOptions& o)
    : Integrator(o.iterations), c_(c), o_(o) {
  validate(o);
  if (!(c.beta > 0.0))
    throw std::invalid_argument("implicit Newmark-family scheme needs beta > 0, got " + std::to_string(c.beta));
  // Lagrange weights at x = i/N for nodes x_j = j - p + 1, j = 0..p.
  const int p = o.poly_order;
  const int n_it = o.iterations;
  weights_.assign(static_cast<std::size_t>(n_it * (p + 1)), 0.0);
  for (int i = 1; i <= n_it; ++i) {
    const double x = static_cast<double>(i) / n_it;
    for (int j = 0; j <= p; ++j) {
      double w = 1.0;
      const double xj = j - p + 1;
      for (int k = 0; k <= p; ++k)
        if (k != j) w *= (x - (k - p + 1)) / (xj - (k - p + 1));
      weights_[static_cast<std::size_t>((i - 1) * (p + 1) + j)] = w;
    }
  }
}

void FixedIterationImplicitEngine::on_configure() {
  const double dt = dt_s_;
  const double c0 = 1.0 / (c_.beta * dt * dt);
  const double c1 = c_.gamma / (c_.beta * dt);
  const double sm = 1.0 - c_.alpha_m;
  const double sf = 1.0 - c_.alpha_f;
  const linalg::StructuralMatrix k_hat =
      linalg::StructuralMatrix::linear_combination(sm * c0, mass_, sf * c1, damping_, sf, stiffness_).compacted();
  k_hat_solver_.factorize(k_hat,
                          "effective stiffness (1-alpha_m)/(beta dt^2) M + "
                          "(1-alpha_f) gamma/(beta dt) C + (1-alpha_f) K0");
  k_dynamic_ =
      linalg::StructuralMatrix::linear_combination(sm * c0, mass_, sf * c1, damping_, 0.0, stiffness_).compacted();
  history_.assign(static_cast<std::size_t>(o_.poly_order - 1), Eigen::VectorXd::Zero(n_));
  for (auto* v : {&a_pred_, &v_pred_, &r_const_, &residual_, &delta_, &target_, &tmp_, &r_meas_}) v->setZero(n_);
}

void FixedIterationImplicitEngine::on_set_state() {
  for (auto& h : history_) h = d_;
}

void FixedIterationImplicitEngine::interpolate(int i, const Eigen::VectorXd& target) {
  const int p = o_.poly_order;
  const double* w = &weights_[static_cast<std::size_t>((i - 1) * (p + 1))];
  command_ = w[p] * target + w[p - 1] * d_;
  for (int k = 2; k <= p; ++k) command_ += w[p - k] * history_[static_cast<std::size_t>(k - 2)];
}

void FixedIterationImplicitEngine::iterate(int i, const Eigen::VectorXd& r) {
  // residual = r_const - K_dyn (U - U_t) - (1 - af) R(U)
  residual_ = r_const_ - (1.0 - c_.alpha_f) * r;
  tmp_ = command_ - d_;
  k_dynamic_.multiply_add(-1.0, tmp_, residual_);
  k_hat_solver_.solve(residual_, delta_);
  target_ = command_ + delta_;
  interpolate(i, target_);
}

void FixedIterationImplicitEngine::on_begin_step() {
  const double dt = dt_s_;
  const double c0 = 1.0 / (c_.beta * dt * dt);
  const double am = c_.alpha_m;
  const double af = c_.alpha_f;
  // Newmark acceleration and velocity if U stayed at U_t.
  a_pred_ = (-c0 * dt) * v_ - (0.5 / c_.beta - 1.0) * a_;
  v_pred_ = v_ + (dt * (1.0 - c_.gamma)) * a_ + (c_.gamma * dt) * a_pred_;
  r_const_ = (1.0 - af) * f_next_ + af * (f_ - r_);
  tmp_ = (1.0 - am) * a_pred_ + am * a_;
  mass_.multiply_add(-1.0, tmp_, r_const_);
  tmp_ = (1.0 - af) * v_pred_ + af * v_;
  damping_.multiply_add(-1.0, tmp_, r_const_);
  // First iteration starts at U = U_t, where R(U_t) is already known: no new measurement.
  command_ = d_;
  iterate(1, r_);
}

void FixedIterationImplicitEngine::on_restoring_force(int iteration, const Eigen::VectorXd& r) {
  if (iteration + 1 < o_.iterations)
    iterate(iteration + 2, r);
  else
    r_meas_ = r;
}

void FixedIterationImplicitEngine::on_end_step() {
  const double dt = dt_s_;
  const double c0 = 1.0 / (c_.beta * dt * dt);
  tmp_ = command_ - d_;  // U_N - U_t
  a_ = a_pred_ + c0 * tmp_;
  v_ = v_pred_ + (c_.gamma * dt * c0) * tmp_;
  // Shift the displacement history: U_{t-2} <- U_{t-1} <- U_t <- U_N.
  for (std::size_t k = history_.size(); k-- > 1;) history_[k].swap(history_[k - 1]);
  if (!history_.empty()) history_[0].swap(d_);
  d_ = command_;
  r_ = r_meas_;
}

}  // namespace rpsd::integrators
