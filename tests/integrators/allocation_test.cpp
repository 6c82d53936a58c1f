// Zero heap allocations on the stepping path: this binary replaces the global operator
// new/delete AND the C allocation functions (Eigen allocates with malloc, not new), counts
// calls while a flag is set, and runs 10,000 steps of a 500-DOF sparse model per scheme: every
// scheme of IntegratorKinds with its default parameters, and the typed suite's configurations.
#include "rpsd/integrators/factory.h"
#include "rpsd/substructure/frame_model.h"
#include "scheme_traits.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "allocation_counter.h"
#include "kind_types.h"

namespace rpsd::integrators::test {
namespace {

using substructure::make_frame_model;
using substructure::permuted;

template <class T>
class ZeroAllocation : public ::testing::Test {};
TYPED_TEST_SUITE(ZeroAllocation, Schemes, SchemeNames);

// Every registered kind, so that a new scheme is covered without a line here.
template <class Kind>
class EveryKindZeroAllocation : public ::testing::Test {};
TYPED_TEST_SUITE(EveryKindZeroAllocation, rpsd::testing::KindTypes<IntegratorKinds>::type, rpsd::testing::KindNames);

// Counts allocations over `steps` hybrid steps with R = K d; sanity-checks the counter.
long allocations_over_steps(Integrator& integrator, const StructuralMatrices& model,
                            const Eigen::SparseMatrix<double>& k, int steps) {
  const auto n = k.rows();
  integrator.configure(model, 1.0 / 4096.0);
  Eigen::VectorXd d0 = Eigen::VectorXd::LinSpaced(n, 0.0, 1e-3);
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd r = k * d0;
  integrator.initialize(d0, zero, r, zero);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  rpsd::testing::begin_counting_allocations();
  bool ok = true;
  for (int s = 0; s < steps; ++s) {
    f(0) = std::sin(1e-3 * s);
    ok &= integrator.begin_step(f) == StepStatus::kOk;
    for (int i = 0; i < integrator.iterations_per_step(); ++i) {
      r.noalias() = k * integrator.target_displacement();
      ok &= integrator.set_measured_restoring_force(r) == StepStatus::kOk;
    }
    ok &= integrator.end_step() == StepStatus::kOk;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_TRUE(ok);
  EXPECT_TRUE(integrator.displacement().allFinite());
  return allocations;
}

TEST(AllocationCounter, SeesEigenAndNewAllocations) {
  rpsd::testing::begin_counting_allocations();
  Eigen::VectorXd v(1000);
  auto* p = new int(3);
  rpsd::testing::keep(p);
  const auto counts = rpsd::testing::end_counting_allocations();
  delete p;
  EXPECT_GE(counts.operator_new, 1);
  EXPECT_GE(counts.c_allocations, 1);
  v.setZero();
}

TYPED_TEST(ZeroAllocation, SparseLumpedMass500DofTenThousandSteps) {
  const auto model = make_frame_model(500, 2.0 * 2.0 * 3.14159 * 4096.0 / 6.3);  // Omega_max < 1
  auto integrator = make_integrator(TypeParam::config());
  EXPECT_EQ(allocations_over_steps(*integrator, StructuralMatrices::sparse(model.mass, model.damping, model.stiffness),
                                   model.stiffness, 10000),
            0);
}

TYPED_TEST(ZeroAllocation, SparseConsistentMass500Dof) {
  const auto model = make_frame_model(500, 4096.0, true);
  auto integrator = make_integrator(TypeParam::config());
  EXPECT_EQ(allocations_over_steps(*integrator, StructuralMatrices::sparse(model.mass, model.damping, model.stiffness),
                                   model.stiffness, 2000),
            0);
}

// Renumbered DOFs: the solvers pick the AMD ordering, whose permutation must not allocate.
TYPED_TEST(ZeroAllocation, SparsePermutedConsistentMass500Dof) {
  const auto model = permuted(make_frame_model(500, 4096.0, true));
  auto integrator = make_integrator(TypeParam::config());
  EXPECT_EQ(allocations_over_steps(*integrator, StructuralMatrices::sparse(model.mass, model.damping, model.stiffness),
                                   model.stiffness, 1000),
            0);
}

TYPED_TEST(ZeroAllocation, Dense60Dof) {
  const auto model = make_frame_model(60, 4096.0, true);
  auto integrator = make_integrator(TypeParam::config());
  const Eigen::MatrixXd M = model.mass, C = model.damping, K = model.stiffness;
  EXPECT_EQ(allocations_over_steps(*integrator, StructuralMatrices::dense(M, C, K), model.stiffness, 2000), 0);
}

TYPED_TEST(EveryKindZeroAllocation, SparseLumpedMass500DofDefaultParameters) {
  const auto model = make_frame_model(500, 2.0 * 2.0 * 3.14159 * 4096.0 / 6.3);  // Omega_max < 1
  auto integrator = make_integrator(TypeParam{});
  EXPECT_EQ(integrator->info().name, TypeParam::kName);
  EXPECT_EQ(allocations_over_steps(*integrator, StructuralMatrices::sparse(model.mass, model.damping, model.stiffness),
                                   model.stiffness, 2000),
            0);
}

}  // namespace
}  // namespace rpsd::integrators::test
