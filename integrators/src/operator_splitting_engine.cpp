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
  one_dof_ = n_ == 1;
}

void OperatorSplittingEngine::on_begin_step() {
  if (one_dof_) {
    begin_step_of<1>();
  } else {
    begin_step_of<Eigen::Dynamic>();
  }
}

void OperatorSplittingEngine::on_restoring_force(int /*iteration*/, const Eigen::VectorXd& r) {
  if (one_dof_) {
    restoring_force_of<1>(r);
  } else {
    restoring_force_of<Eigen::Dynamic>(r);
  }
}

void OperatorSplittingEngine::on_end_step() {
  if (one_dof_) {
    end_step_of<1>();
  } else {
    end_step_of<Eigen::Dynamic>();
  }
}

// The predictor and corrector entry by entry in plain loops, each entry computed in the order
// of the formulas above (the same digits as Eigen's expressions): for the few DOFs of a hybrid
// test's model, Eigen's set-up per expression costs more than the arithmetic.
template <int N>
void OperatorSplittingEngine::begin_step_of() {
  const Eigen::Index n = N == Eigen::Dynamic ? n_ : N;
  const double dt = dt_s_;
  const double c_a = dt * dt * (0.5 - c_.beta), c_v = dt * (1.0 - c_.gamma);
  const double *d = d_.data(), *v = v_.data(), *a = a_.data();
  double *command = command_.data(), *v_pred = v_pred_.data();
  for (Eigen::Index i = 0; i < n; ++i) {
    command[i] = d[i] + dt * v[i] + c_a * a[i];
    v_pred[i] = v[i] + c_v * a[i];
  }
}

template <int N>
void OperatorSplittingEngine::restoring_force_of(const Eigen::VectorXd& r) {
  const Eigen::Index n = N == Eigen::Dynamic ? n_ : N;
  const double* from = r.data();
  double* to = r_meas_.data();
  for (Eigen::Index i = 0; i < n; ++i) to[i] = from[i];
}

template <int N>
void OperatorSplittingEngine::end_step_of() {
  const Eigen::Index n = N == Eigen::Dynamic ? n_ : N;
  const double a = c_.alpha;
  const double s = 1.0 + a;
  const double dt = dt_s_;
  {
    const double *f_next = f_next_.data(), *f = f_.data(), *r_meas = r_meas_.data(), *r = r_.data();
    double* rhs = rhs_.data();
    for (Eigen::Index i = 0; i < n; ++i) rhs[i] = s * f_next[i] - a * f[i] - s * r_meas[i] + a * r[i];
  }
  damping_.multiply_add<N>(-s, v_pred_, rhs_);
  if (a != 0.0) damping_.multiply_add<N>(a, v_, rhs_);
  effective_mass_solver_.solve<N>(rhs_, a_next_);

  const double bdt2 = c_.beta * dt * dt, gdt = c_.gamma * dt;
  {
    const double *command = command_.data(), *v_pred = v_pred_.data(), *a_next = a_next_.data();
    double *d = d_.data(), *v = v_.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      d[i] = command[i] + bdt2 * a_next[i];
      v[i] = v_pred[i] + gdt * a_next[i];
    }
  }
  // R+ = R~+ (+ beta dt^2 K_I a+): the measured force becomes the state's; r_meas_ is written
  // again by the next step's measurement before it is read.
  take<N>(r_, r_meas_);
  if (bdt2 != 0.0) stiffness_.multiply_add<N>(bdt2, a_next_, r_);
  take<N>(a_, a_next_);
}

// to = from, by a swap of the two vectors' storage (`from` is scratch after it), or, for a size
// known to be 1, by copying the entry: one move instead of swapping two pointers and sizes.
template <int N>
void OperatorSplittingEngine::take(Eigen::VectorXd& to, Eigen::VectorXd& from) noexcept {
  if constexpr (N == Eigen::Dynamic) {
    to.swap(from);
  } else {
    for (Eigen::Index i = 0; i < N; ++i) to.data()[i] = from.data()[i];
  }
}

}  // namespace rpsd::integrators
