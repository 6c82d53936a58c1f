#include "rpsd/integrators/integrator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rpsd::integrators {
namespace {

std::string dims(const linalg::StructuralMatrix& m) {
  return std::to_string(m.rows()) + "x" + std::to_string(m.cols());
}

void check_matrices(const linalg::StructuralMatrix& M, const linalg::StructuralMatrix& C,
                    const linalg::StructuralMatrix& K) {
  if (M.rows() == 0 || M.rows() != M.cols())
    throw std::invalid_argument("mass matrix must be square and non-empty, got " + dims(M));
  const auto n = M.rows();
  if (C.rows() != n || C.cols() != n)
    throw std::invalid_argument("damping matrix is " + dims(C) + ", expected " + dims(M) + " like the mass matrix");
  if (K.rows() != n || K.cols() != n)
    throw std::invalid_argument("initial stiffness matrix is " + dims(K) + ", expected " + dims(M) +
                                " like the mass matrix");
  if (!M.all_finite()) throw std::invalid_argument("mass matrix has a NaN or infinite entry");
  if (!C.all_finite()) throw std::invalid_argument("damping matrix has a NaN or infinite entry");
  if (!K.all_finite()) throw std::invalid_argument("initial stiffness matrix has a NaN or infinite entry");
  if (!M.is_symmetric()) throw std::invalid_argument("mass matrix is not symmetric");
  if (!C.is_symmetric()) throw std::invalid_argument("damping matrix is not symmetric");
  if (!K.is_symmetric()) throw std::invalid_argument("initial stiffness matrix is not symmetric");
  if (!is_positive_definite(M)) throw std::invalid_argument("mass matrix is not positive definite");
}

}  // namespace

void Integrator::configure(const StructuralMatrices& matrices, double dt_s, const ConfigureOptions& options) {
  phase_ = Phase::kUnconfigured;
  if (!(dt_s > 0.0) || !std::isfinite(dt_s))
    throw std::invalid_argument("time step dt_s must be positive and finite, got " +
                                (std::ostringstream() << dt_s).str());
  mass_ = matrices.mass_kg.compacted();
  damping_ = matrices.damping_n_s_per_m.compacted();
  stiffness_ = matrices.initial_stiffness_n_per_m.compacted();
  check_matrices(mass_, damping_, stiffness_);
  n_ = mass_.rows();
  dt_s_ = dt_s;
  mass_solver_.factorize(mass_, "mass matrix");

  const double limit = info().stability_limit_omega_dt;
  omega_max_ = std::numeric_limits<double>::quiet_NaN();
  if (std::isfinite(limit)) {
    // A cheap upper bound proves most time steps stable; estimate only when it does not.
    omega_max_ = frequency_upper_bound_rad_s(mass_, stiffness_);
    if (!(omega_max_ * dt_s <= limit))
      omega_max_ = integrators::max_natural_frequency_rad_s(mass_, stiffness_, mass_solver_);
    const double omega_dt = omega_max_ * dt_s;
    if (options.reject_unstable_time_step && omega_dt > limit) {
      std::ostringstream msg;
      msg << "unstable time step for " << info().name << ": omega_max*dt = " << omega_dt
          << " exceeds the stability limit " << limit << " (omega_max = " << omega_max_ << " rad/s, dt = " << dt_s
          << " s); use dt <= " << limit / omega_max_ << " s";
      throw std::invalid_argument(msg.str());
    }
  }

  for (auto* v : {&d_, &v_, &a_, &r_, &f_, &f_next_, &command_}) v->setZero(n_);
  on_configure();
  phase_ = Phase::kConfigured;
}

void Integrator::check_size(const Eigen::VectorXd& x, const char* what) const {
  if (x.size() != n_)
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(x.size()) + " entries, expected " +
                                std::to_string(n_));
  if (!x.allFinite()) throw std::invalid_argument(std::string(what) + " has a NaN or infinite entry");
}

void Integrator::initialize(const Eigen::VectorXd& d0, const Eigen::VectorXd& v0, const Eigen::VectorXd& r0,
                            const Eigen::VectorXd& f0) {
  if (phase_ == Phase::kUnconfigured) throw std::logic_error("initialize() before configure()");
  check_size(d0, "initial displacement");
  check_size(v0, "initial velocity");
  check_size(r0, "initial restoring force");
  check_size(f0, "initial external force");
  Eigen::VectorXd rhs = f0 - r0;
  damping_.multiply_add(-1.0, v0, rhs);
  Eigen::VectorXd a0(n_);
  mass_solver_.solve(rhs, a0);
  set_state(d0, v0, a0, r0, f0);
}

void Integrator::set_state(const Eigen::VectorXd& d, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                           const Eigen::VectorXd& r, const Eigen::VectorXd& f, double time_s, std::int64_t step) {
  if (phase_ == Phase::kUnconfigured) throw std::logic_error("set_state() before configure()");
  check_size(d, "displacement");
  check_size(v, "velocity");
  check_size(a, "acceleration");
  check_size(r, "restoring force");
  check_size(f, "external force");
  d_ = d;
  v_ = v;
  a_ = a;
  r_ = r;
  f_ = f;
  command_ = d;
  time_s_ = time_s;
  step_ = step;
  time0_s_ = time_s;
  step0_ = step;
  on_set_state();
  phase_ = Phase::kIdle;
}

StepStatus Integrator::sequence_error() const {
  return phase_ == Phase::kUnconfigured || phase_ == Phase::kConfigured ? StepStatus::kNotInitialized
                                                                        : StepStatus::kOutOfSequence;
}

}  // namespace rpsd::integrators
