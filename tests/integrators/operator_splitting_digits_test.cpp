// Central difference and alpha-OS step in plain loops (docs/performance.md, "The loop's
// instructions"): each state they give must carry the very digits of the schemes' formulas
// written as Eigen expressions, as they were, or every example's records would change.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>

#include "rpsd/integrators/alpha_os.h"
#include "rpsd/integrators/central_difference.h"
#include "rpsd/integrators/symmetric_solver.h"

namespace rpsd::integrators {
namespace {

// y += s A x as Eigen evaluates it, for the storages the models here use.
void multiply_add(const linalg::StructuralMatrix& A, double s, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  if (A.is_diagonal()) {
    y.array() += s * A.diagonal_values().array() * x.array();
  } else {
    y.noalias() += s * (A.dense() * x);
  }
}

// The predictor-corrector of operator_splitting_engine.h in Eigen expressions.
class Reference {
 public:
  Reference(const StructuralMatrices& m, double dt, const OperatorSplittingCoefficients& c)
      : C_(m.damping_n_s_per_m.compacted()), K_(m.initial_stiffness_n_per_m.compacted()), dt_(dt), c_(c) {
    const double s = 1.0 + c.alpha;
    const linalg::StructuralMatrix m_hat =
        linalg::StructuralMatrix::linear_combination(1.0, m.mass_kg.compacted(), s * c.gamma * dt, C_,
                                                     s * c.beta * dt * dt, K_)
            .compacted();
    diagonal_ = m_hat.is_diagonal();
    if (diagonal_) inverse_ = m_hat.diagonal_values().cwiseInverse();
    solver_.factorize(m_hat, "M hat");
  }

  void set_state(const Eigen::VectorXd& d, const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& r,
                 const Eigen::VectorXd& f) {
    d_ = d, v_ = v, a_ = a, r_ = r, f_ = f;
  }

  const Eigen::VectorXd& begin_step() {
    const double dt = dt_;
    command_ = d_ + dt * v_ + (dt * dt * (0.5 - c_.beta)) * a_;
    v_pred_ = v_ + (dt * (1.0 - c_.gamma)) * a_;
    return command_;
  }

  void end_step(const Eigen::VectorXd& f_next, const Eigen::VectorXd& r_meas) {
    const double a = c_.alpha, s = 1.0 + a, dt = dt_;
    Eigen::VectorXd rhs = s * f_next - a * f_ - s * r_meas + a * r_;
    multiply_add(C_, -s, v_pred_, rhs);
    if (a != 0.0) multiply_add(C_, a, v_, rhs);
    Eigen::VectorXd a_next(rhs.size());
    if (diagonal_) {
      a_next.array() = inverse_.array() * rhs.array();
    } else {
      solver_.solve(rhs, a_next);
    }
    const double bdt2 = c_.beta * dt * dt;
    d_ = command_ + bdt2 * a_next;
    v_ = v_pred_ + (c_.gamma * dt) * a_next;
    r_ = r_meas;
    if (bdt2 != 0.0) multiply_add(K_, bdt2, a_next, r_);
    a_ = a_next;
    f_ = f_next;
  }

  Eigen::VectorXd d_, v_, a_, r_, f_;

 private:
  linalg::StructuralMatrix C_, K_;
  double dt_;
  OperatorSplittingCoefficients c_;
  bool diagonal_ = false;
  Eigen::VectorXd inverse_, command_, v_pred_;
  SymmetricSolver solver_;
};

void expect_same_bits(const Eigen::VectorXd& got, const Eigen::VectorXd& want, const char* what, int step) {
  ASSERT_EQ(got.size(), want.size());
  for (Eigen::Index i = 0; i < got.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got[i]), std::bit_cast<std::uint64_t>(want[i]))
        << what << "[" << i << "] at step " << step << ": " << got[i] << " against " << want[i];
  }
}

// 300 steps of a softening-hardening model under a sine force, from a state with a -0 in it.
void expect_formulas_digits(Integrator& integrator, const StructuralMatrices& m, double dt,
                            const OperatorSplittingCoefficients& c) {
  const Eigen::Index n = m.mass_kg.rows();
  integrator.configure(m, dt);
  Reference reference(m, dt, c);
  Eigen::VectorXd d0 = Eigen::VectorXd::LinSpaced(n, 1e-3, 3e-3), v0 = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd a0 = Eigen::VectorXd::Constant(n, -0.0), r0 = Eigen::VectorXd::Zero(n), f0 = -a0;
  d0[0] = -0.0;
  integrator.set_state(d0, v0, a0, r0, f0);
  reference.set_state(d0, v0, a0, r0, f0);
  const linalg::StructuralMatrix K = m.initial_stiffness_n_per_m;
  for (int step = 1; step <= 300; ++step) {
    const Eigen::VectorXd f = Eigen::VectorXd::Constant(n, 2e3 * std::sin(0.05 * step));
    ASSERT_EQ(integrator.begin_step(f), StepStatus::kOk);
    const Eigen::VectorXd& command = integrator.target_displacement();
    expect_same_bits(command, reference.begin_step(), "command", step);
    Eigen::VectorXd r(n);
    K.multiply(command, r);
    r.array() -= 4e7 * command.array().cube();
    ASSERT_EQ(integrator.set_measured_restoring_force(r), StepStatus::kOk);
    ASSERT_EQ(integrator.end_step(), StepStatus::kOk);
    reference.end_step(f, r);
    expect_same_bits(integrator.displacement(), reference.d_, "d", step);
    expect_same_bits(integrator.velocity(), reference.v_, "v", step);
    expect_same_bits(integrator.acceleration(), reference.a_, "a", step);
    expect_same_bits(integrator.restoring_force(), reference.r_, "r", step);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(OperatorSplittingDigits, CentralDifferenceOnThePapersSdofGivesTheFormulasDigits) {
  const auto m =
      StructuralMatrices::dense(Eigen::MatrixXd::Constant(1, 1, 1000.0), Eigen::MatrixXd::Constant(1, 1, 1.5e3),
                                Eigen::MatrixXd::Constant(1, 1, 700.8e3));
  CentralDifference integrator;
  expect_formulas_digits(integrator, m, 1.0 / 1024.0, {0.0, 0.0, 0.5});
}

TEST(OperatorSplittingDigits, AlphaOsOnACoupledModelGivesTheFormulasDigits) {
  Eigen::MatrixXd k(3, 3), c(3, 3);
  k << 4e6, -2e6, 0.0, -2e6, 4e6, -2e6, 0.0, -2e6, 2e6;
  c = 1e-3 * k;
  c.diagonal().array() += 50.0;
  const Eigen::MatrixXd mass = Eigen::Vector3d(1e3, 1.2e3, 0.8e3).asDiagonal();
  const AlphaOsParameters p{-0.1};
  AlphaOs integrator(p);
  const double a = p.alpha;
  expect_formulas_digits(integrator, StructuralMatrices::dense(mass, c, k), 0.005,
                         {a, (1.0 - a) * (1.0 - a) / 4.0, (1.0 - 2.0 * a) / 2.0});
  // A lumped mass and damping: the diagonal solve and products.
  AlphaOs lumped(p);
  const Eigen::MatrixXd c_lumped = Eigen::Vector3d(40.0, 55.0, 30.0).asDiagonal();
  expect_formulas_digits(lumped, StructuralMatrices::dense(mass, c_lumped, k), 0.005,
                         {a, (1.0 - a) * (1.0 - a) / 4.0, (1.0 - 2.0 * a) / 2.0});
}

}  // namespace
}  // namespace rpsd::integrators
