#pragma once
// One interface for every time-stepping scheme, shaped for hybrid testing:
//
//   configure(matrices, dt)            once; factorisations; input checks (throws)
//   initialize(d0, v0, r0, f0)         a0 from equilibrium
//   per step:
//     begin_step(f_next)               external force at t + dt
//     for i in [0, iterations_per_step()):
//       send target_displacement()     (explicit schemes: known before any force of
//                                       the step is measured)
//       set_measured_restoring_force(R(command))   TOTAL restoring force at the command
//     end_step()                       d, v, a at t + dt
//
// Everything in the per-step group is real-time safe: no allocation, no exceptions;
// misuse is reported through StepStatus.
#include "rpsd/integrators/structural_matrices.h"
#include "rpsd/integrators/symmetric_solver.h"
#include "rpsd/linalg/structural_matrix.h"

#include <Eigen/Dense>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>

namespace rpsd::integrators {

struct SchemeInfo {
  std::string_view name;  // its parameters' kName
  // The first command of a step depends only on the state at t (no force of the step).
  bool explicit_in_displacement;
  // Omega = omega*dt above which the scheme is unstable on a linear undamped system;
  // +infinity for unconditionally stable schemes.
  double stability_limit_omega_dt;
};

enum class StepStatus : std::uint8_t {
  kOk,
  kNotInitialized,  // configure() and initialize() (or set_state()) first
  kOutOfSequence,   // begin_step / set_measured_restoring_force / end_step order violated
  kSizeMismatch,    // vector length differs from the model size
  kNonFiniteInput,  // NaN or infinity in a force
};

struct ConfigureOptions {
  // Reject a dt beyond the scheme's stability limit (omega_max dt > limit). Amplification
  // analysis turns this off to study unstable steps on purpose.
  bool reject_unstable_time_step = true;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  // Not real-time safe. Checks the matrices (square, same size, finite, symmetric, mass
  // positive definite), dt > 0, and dt against the stability limit; factorises once.
  // Throws std::invalid_argument with a message naming the problem.
  void configure(const StructuralMatrices& matrices, double dt_s, const ConfigureOptions& options = {});

  // Not real-time safe (throws on bad sizes). a0 = M^-1 (f0 - C v0 - r0).
  void initialize(const Eigen::VectorXd& d0, const Eigen::VectorXd& v0, const Eigen::VectorXd& r0,
                  const Eigen::VectorXd& f0);
  // Not real-time safe. Sets an arbitrary state (restart, amplification analysis):
  // displacement, velocity, acceleration, restoring force R(d) and external force at t.
  void set_state(const Eigen::VectorXd& d, const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& r,
                 const Eigen::VectorXd& f, double time_s = 0.0, std::int64_t step = 0);

  // Real-time safe. External force at t + dt; computes the first command.
  StepStatus begin_step(const Eigen::VectorXd& f_next);
  // Commands (and force measurements) per step: 1 for explicit schemes.
  int iterations_per_step() const { return iterations_; }
  // Real-time safe. The displacement command of the current iteration.
  const Eigen::VectorXd& target_displacement() const { return command_; }
  // Real-time safe. Total restoring force R measured/computed at target_displacement().
  StepStatus set_measured_restoring_force(const Eigen::VectorXd& r);
  // Real-time safe. Completes the step: displacement, velocity, acceleration at t + dt.
  StepStatus end_step();

  const Eigen::VectorXd& displacement() const { return d_; }
  const Eigen::VectorXd& velocity() const { return v_; }
  const Eigen::VectorXd& acceleration() const { return a_; }
  // Restoring force at displacement() (for alpha-OS: corrected with K_I).
  const Eigen::VectorXd& restoring_force() const { return r_; }
  double time_s() const { return time_s_; }
  std::int64_t step() const { return step_; }
  double dt_s() const { return dt_s_; }
  Eigen::Index size() const { return n_; }
  // omega_max of (K0, M) used by the stability check (conditionally stable schemes only,
  // else NaN): a Gershgorin upper bound for a lumped mass when that already proves the
  // step stable, otherwise the exact value or a Lanczos estimate.
  double max_natural_frequency_rad_s() const { return omega_max_; }

  virtual SchemeInfo info() const = 0;

 protected:
  explicit Integrator(int iterations_per_step = 1) : iterations_(iterations_per_step) {}

  // Scheme hooks. The base checks sizes and sequence before calling them.
  virtual void on_configure() = 0;   // factorise scheme matrices (may throw)
  virtual void on_set_state() = 0;   // derive scheme state from d_, v_, a_, r_, f_
  virtual void on_begin_step() = 0;  // f_next_ is set: write the first command_
  virtual void on_restoring_force(int iteration, const Eigen::VectorXd& r) = 0;
  virtual void on_end_step() = 0;  // set d_, v_, a_, r_ at t + dt

  void set_iterations_per_step(int n) { iterations_ = n; }

  // Model (set by configure).
  linalg::StructuralMatrix mass_, damping_, stiffness_;
  SymmetricSolver mass_solver_;
  double dt_s_ = 0.0;
  Eigen::Index n_ = 0;
  // State at t, the force at t + dt, and the current command.
  Eigen::VectorXd d_, v_, a_, r_, f_, f_next_, command_;
  double time_s_ = 0.0;
  std::int64_t step_ = 0;

 private:
  enum class Phase : std::uint8_t { kUnconfigured, kConfigured, kIdle, kIterating, kAwaitingEnd };
  void check_size(const Eigen::VectorXd& x, const char* what) const;
  StepStatus sequence_error() const;  // the status of a per-step call in the wrong phase
  // Every entry finite, in a plain loop: Eigen's allFinite() costs more in set-up than the
  // check itself for the few DOFs of a hybrid test's model.
  static bool all_finite(const Eigen::VectorXd& x) {
    const double* p = x.data();
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (!std::isfinite(p[i])) return false;
    }
    return true;
  }

  int iterations_ = 1;
  int iteration_ = 0;
  Phase phase_ = Phase::kUnconfigured;
  double omega_max_ = std::numeric_limits<double>::quiet_NaN();
  // time = time0 + (step - step0) dt, so that time does not accumulate round-off.
  double time0_s_ = 0.0;
  std::int64_t step0_ = 0;
};

// The per-step calls are inline: each checks its phase (one comparison on the way through;
// which error a wrong phase is, sequence_error works out), the size and finiteness of what
// it is given, then calls the scheme's hook; a call of its own would cost more than the checks.
inline StepStatus Integrator::begin_step(const Eigen::VectorXd& f_next) {
  if (phase_ != Phase::kIdle) return sequence_error();
  if (f_next.size() != n_) return StepStatus::kSizeMismatch;
  if (!all_finite(f_next)) return StepStatus::kNonFiniteInput;
  const double* from = f_next.data();  // a plain loop: std::copy_n would call memmove
  double* to = f_next_.data();
  for (Eigen::Index i = 0; i < n_; ++i) to[i] = from[i];
  iteration_ = 0;
  on_begin_step();
  phase_ = Phase::kIterating;
  return StepStatus::kOk;
}

inline StepStatus Integrator::set_measured_restoring_force(const Eigen::VectorXd& r) {
  if (phase_ != Phase::kIterating) return sequence_error();
  if (r.size() != n_) return StepStatus::kSizeMismatch;
  if (!all_finite(r)) return StepStatus::kNonFiniteInput;
  on_restoring_force(iteration_, r);
  if (++iteration_ == iterations_) phase_ = Phase::kAwaitingEnd;
  return StepStatus::kOk;
}

inline StepStatus Integrator::end_step() {
  if (phase_ != Phase::kAwaitingEnd) return sequence_error();
  on_end_step();
  f_.swap(f_next_);
  ++step_;
  time_s_ = time0_s_ + static_cast<double>(step_ - step0_) * dt_s_;
  phase_ = Phase::kIdle;
  return StepStatus::kOk;
}

}  // namespace rpsd::integrators
