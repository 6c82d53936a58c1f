// Zero heap allocations on the real-time path: restoring_force / commit / tangent_stiffness
// of a 500-DOF sparse and a 200-DOF dense linear model and of a 50-story building of every
// story spring kind, with the partition and the ground-motion load, over many steps.
//
// This binary replaces the global operator new/delete and the C allocation functions
// (malloc, calloc, realloc, aligned variants; glibc allows replacing them and exports the
// __libc_* originals) and counts calls while a window is open. Eigen allocates with malloc,
// not operator new, so counting malloc too catches hidden Eigen temporaries.

#include "rpsd/substructure/ground_motion_load.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/substructure/partition.h"
#include "rpsd/substructure/shear_building.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "allocation_counter.h"
#include "kind_types.h"

namespace rpsd::substructure {
namespace {

struct Counts {
  long mallocs, news;
};

// Runs f with counting on; returns what it allocated.
template <typename F>
Counts count_allocations(F&& f) {
  rpsd::testing::begin_counting_allocations();
  f();
  const auto counts = rpsd::testing::end_counting_allocations();
  return {counts.c_allocations, counts.operator_new};
}

TEST(NoAllocation, TheCounterSeesAllocations) {
  // Guards against a hook that counts nothing.
  const Counts c = count_allocations([] {
    auto* p = new int(3);
    rpsd::testing::keep(p);
    delete p;
    Eigen::VectorXd v(1000);  // Eigen heap buffer through malloc
    v.setOnes();
    void* q = std::malloc(16);
    rpsd::testing::keep(q);
    std::free(q);
  });
  EXPECT_EQ(c.news, 1);
  EXPECT_GE(c.mallocs, 2);  // Eigen's buffer and the malloc (new no longer goes through malloc)
}

// A 500-DOF model banded like a 2-D frame (half-bandwidth 15, bandwidth about 30),
// diagonally dominant so that it is positive definite.
LinearMdofParameters banded_model(Eigen::Index n, Eigen::Index half_band) {
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (Eigen::Index i = 0; i < n; ++i) {
    mt.emplace_back(i, i, 500.0 + (i % 7) * 10.0);
    double offsum = 0.0;
    for (Eigen::Index j = std::max<Eigen::Index>(0, i - half_band); j < std::min(n, i + half_band + 1); ++j) {
      if (j == i) continue;
      const double v = -1.0e6 / (1.0 + static_cast<double>(std::abs(i - j)));
      kt.emplace_back(i, j, v);
      offsum += std::abs(v);
    }
    kt.emplace_back(i, i, offsum + 2.0e6);
  }
  linalg::SparseMatrix K(n, n), M(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
  LinearMdofParameters c;
  c.mass_kg = linalg::StructuralMatrix(std::move(M));
  c.stiffness_n_per_m = linalg::StructuralMatrix(std::move(K));
  c.damping = RayleighFromModes{1, 5, 0.05, 0.05};
  return c;
}

constexpr int kSteps = 10000;

TEST(NoAllocation, SparseLinearModel500Dofs) {
  const Eigen::Index n = 500;
  LinearMdofModel model;
  model.configure(banded_model(n, 15));
  ASSERT_TRUE(model.initial_stiffness().is_sparse());
  ASSERT_TRUE(model.damping().is_sparse());
  PartitionConfig pc;
  pc.dofs = n;
  pc.experimental = {{100, 0, 0.5, 4.0, 1e5}, {499, 1, 0.5, 4.0, 1e5}};
  pc.influence = Eigen::VectorXd::Ones(n);
  Partition partition;
  partition.configure(pc);
  GroundMotionLoad load;
  load.configure(model.mass(), partition.influence());

  Eigen::VectorXd d(n), r(n), f(n), u(2), fm(2), scratch(n);
  const Eigen::VectorXd shape = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  double check = 0.0;
  const Counts c = count_allocations([&] {
    for (int k = 0; k < kSteps; ++k) {
      const double s = std::sin(1e-3 * k);
      d = 0.01 * s * shape;  // in-place assignment into a sized vector
      partition.extract_commands(d, u);
      fm = 1e5 * u;
      for (int it = 0; it < 2; ++it) model.restoring_force(d, r);  // two iterations
      partition.add_forces(fm, r);
      model.commit();
      const linalg::StructuralMatrix& Kt = model.tangent_stiffness();
      model.damping().multiply(d, scratch);
      model.mass().multiply_add(1.0, d, scratch);
      Kt.multiply_add(-1.0, d, scratch);
      load.force(0.1 * s, f);
      check += r[n - 1] + f[0] + scratch[0];
    }
  });
  EXPECT_EQ(c.news, 0);
  EXPECT_EQ(c.mallocs, 0);
  EXPECT_TRUE(std::isfinite(check));
}

TEST(NoAllocation, DenseLinearModel) {
  // Dense storage: the GEMV products must not allocate either.
  LinearMdofParameters cfg = banded_model(200, 15);
  cfg.mass_kg = cfg.mass_kg.converted(linalg::MatrixStorage::kDense);
  cfg.stiffness_n_per_m = cfg.stiffness_n_per_m.converted(linalg::MatrixStorage::kDense);
  LinearMdofModel model;
  model.configure(cfg);
  ASSERT_FALSE(model.initial_stiffness().is_sparse());
  ASSERT_FALSE(model.damping().is_sparse());
  const Eigen::Index n = model.dofs();
  Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01), r(n), scratch(n);
  double check = 0.0;
  const Counts c = count_allocations([&] {
    for (int k = 0; k < 2000; ++k) {
      model.restoring_force(d, r);
      model.commit();
      model.damping().multiply(d, scratch);
      model.tangent_stiffness().multiply_add(1.0, d, scratch);
      check += r[0] + scratch[n - 1];
    }
  });
  EXPECT_EQ(c.news, 0);
  EXPECT_EQ(c.mallocs, 0);
  EXPECT_TRUE(std::isfinite(check));
}

ShearBuildingParameters building(int floors, const StorySpringConfig& spring, linalg::MatrixStorage storage) {
  ShearBuildingParameters c;
  c.floor_masses_kg.assign(static_cast<std::size_t>(floors), 5.0e4);
  c.story_springs.assign(static_cast<std::size_t>(floors), spring);
  c.damping = RayleighFromModes{1, 3, 0.05, 0.05};
  c.storage = storage;
  return c;
}

void run_building(ShearBuilding& b) {
  const Eigen::Index n = b.dofs();
  Eigen::VectorXd d(n), r(n), f(n);
  const Eigen::VectorXd shape = Eigen::VectorXd::LinSpaced(n, 1.0, static_cast<double>(n));
  double check = 0.0;
  const Counts c = count_allocations([&] {
    for (int k = 0; k < kSteps; ++k) {
      // Drifts of up to 3 cm per story: well into yielding, with reversals.
      d = 0.03 * std::sin(2e-3 * k) * shape;
      b.restoring_force(d, r);
      b.restoring_force(d, r);
      check += b.tangent_stiffness().coeff(0, 0);
      b.commit();
      check += r[0];
    }
  });
  EXPECT_EQ(c.news, 0);
  EXPECT_EQ(c.mallocs, 0);
  EXPECT_TRUE(std::isfinite(check));
}

// Every story spring of StorySpringKinds, with its example(): a new kind is covered here
// without a new line.
template <class Kind>
class EveryStorySpring : public ::testing::Test {};
TYPED_TEST_SUITE(EveryStorySpring, rpsd::testing::KindTypes<StorySpringKinds>::type, rpsd::testing::KindNames);

TYPED_TEST(EveryStorySpring, Building50Stories) {
  for (linalg::MatrixStorage storage : {linalg::MatrixStorage::kDense, linalg::MatrixStorage::kSparse}) {
    ShearBuilding b;
    b.configure(building(50, TypeParam::example(), storage));
    run_building(b);
  }
}

}  // namespace
}  // namespace rpsd::substructure
