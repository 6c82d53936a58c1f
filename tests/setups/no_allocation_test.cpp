// Zero heap allocations on the real-time path of every setup kind in both geometries: strokes,
// the Jacobian, the Newton solve of measured strokes, DOF forces through Jᵀ and the actuator
// forces that carry DOF forces, over thousands of steps of a moving specimen.
//
// This binary replaces the global allocation functions (rpsd_test_allocation_counter), so
// that a hidden Eigen temporary on the heap is counted too.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rpsd/setups/planar_setup.h"
#include "setup_examples.h"

#include "allocation_counter.h"

namespace rpsd::setups {
namespace {

TEST(SetupAllocation, EveryKindStepsWithoutAllocating) {
  std::vector<PlanarGeometry> all;
  for (const Geometry g : {Geometry::kLinear, Geometry::kLargeDisplacement}) {
    all.push_back(examples::one_actuator(g).planar());
    all.push_back(examples::two_actuators(g).planar());
    all.push_back(examples::three_actuators(g, ActuatorSide::kRight).planar());
    all.push_back(examples::planar(g).planar());
  }
  for (const PlanarGeometry& geometry : all) {
    const PlanarSetup s(geometry);
    const int n = s.dofs();
    SetupVector target(n), strokes(n), measured(n), u = SetupVector::Zero(n), forces(n), f(n), back(n);
    SetupMatrix j(n, n);
    long solved = 0;
    rpsd::testing::begin_counting_allocations();
    for (int step = 0; step < 5000; ++step) {
      const double t = step * 1e-3;
      for (int k = 0; k < n; ++k) target[k] = 0.1 * std::sin(2.0 * t + k) * (k == 2 ? 2.0 : 1.0);
      s.strokes(target, strokes);
      measured = strokes * (1.0 + 1e-4);  // what the actuators reached
      if (s.displacements(measured, u, back) == SetupStatus::kOk) ++solved;
      u = back;
      s.jacobian(u, j);
      for (int k = 0; k < n; ++k) f[k] = 1e4 * std::cos(t + k);
      s.dof_forces(u, f, forces);
      if (s.actuator_forces(u, forces, f) == SetupStatus::kOk) ++solved;
    }
    const rpsd::testing::AllocationCounts counts = rpsd::testing::end_counting_allocations();
    EXPECT_EQ(counts.total(), 0) << "dofs " << n << ", geometry " << static_cast<int>(geometry.geometry);
    EXPECT_EQ(solved, 10000);  // every step really solved (and so took the whole path)
  }
}

}  // namespace
}  // namespace rpsd::setups
