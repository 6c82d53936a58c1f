// Bilinear kinematic-hardening spring against a hand-computed cyclic path.
//
// k0 = 2e6 N/m, fy = 2e4 N (uy = 10 mm), α = 0.1 (post-yield slope 2e5 N/m). Cycle
// 0 → +30 mm → −30 mm → +30 mm, by hand:
//   A  u = +10 mm  F = +20 kN    first yield
//   B  u = +30 mm  F = 20 + 0.2·20 = +24 kN
//   C  u = +10 mm  F = 24 − 2·20 = −16 kN   unloading at k0 over the elastic range 2 fy
//   D  u = −30 mm  F = −16 − 0.2·40 = −24 kN  hardening at α k0
//   E  u = −10 mm  F = −24 + 40 = +16 kN     reloading at k0
//   B  u = +30 mm  F = 16 + 0.2·40 = +24 kN  back to B: the loop closes
// The closed loop B-C-D-E is a parallelogram of area (shoelace on the four corners)
// 1440 J = 4 (1 − α) fy (u_max − uy).

#include "rpsd/substructure/bilinear_spring.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rpsd::substructure {
namespace {

constexpr double k0 = 2.0e6, fy = 2.0e4, alpha = 0.1;

BilinearSpring make() { return BilinearSpring({k0, fy, alpha}); }

// Drives the spring from its committed deformation to `target` in steps of `du`, committing
// each step; returns ∮F du by the trapezoid rule and checks the tangent on each branch.
struct Drive {
  BilinearSpring& s;
  double energy = 0.0;
  void to(double target, double du, double expected_tangent_after_yield, double yield_at) {
    double u = s.committed_deformation();
    double f = s.committed_force();
    const int n = static_cast<int>(std::lround(std::abs(target - u) / du));
    const double step = (target - u) / n;
    for (int i = 1; i <= n; ++i) {
      const double u_new = u + step;
      const double f_new = s.trial(u_new);
      // Branch check away from the kink: elastic before the yield point, hardening after.
      const bool past_yield = (step > 0) ? u_new > yield_at + 1e-9 : u_new < yield_at - 1e-9;
      const bool before_yield = (step > 0) ? u_new < yield_at - 1e-9 : u_new > yield_at + 1e-9;
      if (past_yield) {
        EXPECT_DOUBLE_EQ(s.tangent_stiffness(), expected_tangent_after_yield) << "u = " << u_new;
      }
      if (before_yield) {
        EXPECT_DOUBLE_EQ(s.tangent_stiffness(), k0) << "u = " << u_new;
      }
      energy += 0.5 * (f + f_new) * (u_new - u);
      s.commit();
      u = u_new;
      f = f_new;
    }
  }
};

TEST(BilinearSpring, HandComputedCyclicPath) {
  BilinearSpring s = make();
  EXPECT_EQ(s.initial_stiffness(), k0);
  Drive d{s};
  d.to(0.010, 1e-4, alpha * k0, 0.010);
  EXPECT_NEAR(s.committed_force(), 2.0e4, 1e-6);  // A
  d.to(0.030, 1e-4, alpha * k0, 0.010);
  EXPECT_NEAR(s.committed_force(), 2.4e4, 1e-6);  // B
  EXPECT_NEAR(s.committed_plastic_deformation(), 0.030 - 2.4e4 / k0, 1e-12);
  const double energy_to_B = d.energy;
  d.to(0.020, 1e-4, alpha * k0, 0.010);
  EXPECT_NEAR(s.committed_force(), 4.0e3, 1e-6);  // on the unloading line, slope k0
  d.to(0.010, 1e-4, alpha * k0, 0.010);
  EXPECT_NEAR(s.committed_force(), -1.6e4, 1e-6);  // C
  d.to(-0.030, 1e-4, alpha * k0, 0.010);
  EXPECT_NEAR(s.committed_force(), -2.4e4, 1e-6);  // D
  d.to(-0.010, 1e-4, alpha * k0, -0.010);
  EXPECT_NEAR(s.committed_force(), 1.6e4, 1e-6);  // E
  d.to(0.030, 1e-4, alpha * k0, -0.010);
  EXPECT_NEAR(s.committed_force(), 2.4e4, 1e-6);  // back at B

  // Hysteresis area of B-C-D-E by the shoelace formula on the hand-computed corners.
  const double u[4] = {0.030, 0.010, -0.030, -0.010}, f[4] = {2.4e4, -1.6e4, -2.4e4, 1.6e4};
  double twice_area = 0.0;
  for (int i = 0; i < 4; ++i) twice_area += u[i] * f[(i + 1) % 4] - u[(i + 1) % 4] * f[i];
  const double area = std::abs(twice_area) / 2.0;
  EXPECT_DOUBLE_EQ(area, 1440.0);
  EXPECT_NEAR(4.0 * (1.0 - alpha) * fy * (0.030 - 0.010), area, 1e-9);
  // Energy dissipated in the closed cycle B → C → D → E → B.
  EXPECT_NEAR(d.energy - energy_to_B, area, 1e-6 * area);
}

TEST(BilinearSpring, ExactForAnyIncrementSize) {
  // One increment from 0 to 30 mm lands on B; one back to −30 mm lands on D.
  BilinearSpring s = make();
  EXPECT_NEAR(s.trial(0.030), 2.4e4, 1e-6);
  s.commit();
  EXPECT_NEAR(s.trial(-0.030), -2.4e4, 1e-6);
  EXPECT_DOUBLE_EQ(s.tangent_stiffness(), alpha * k0);
  s.commit();
  EXPECT_NEAR(s.trial(-0.015), 6.0e3, 1e-6);  // elastic reloading from D
  EXPECT_DOUBLE_EQ(s.tangent_stiffness(), k0);
  EXPECT_NEAR(s.trial(-0.010), 1.6e4, 1e-6);  // E, the end of the elastic range
  EXPECT_NEAR(s.trial(0.030), 2.4e4, 1e-6);   // B again, in one increment
}

TEST(BilinearSpring, ElasticPerfectlyPlastic) {
  BilinearSpring s({k0, fy, 0.0});
  EXPECT_NEAR(s.trial(0.05), fy, 1e-9);
  EXPECT_EQ(s.tangent_stiffness(), 0.0);
  s.commit();
  EXPECT_NEAR(s.trial(0.03), fy - k0 * 0.02, 1e-9);  // unloads elastically from the plateau
  s.commit();
  EXPECT_NEAR(s.trial(-0.05), -fy, 1e-9);
}

TEST(BilinearSpring, TrialsDoNotChangeTheCommittedState) {
  BilinearSpring s = make();
  s.trial(0.020);
  s.commit();
  const double f1 = s.trial(0.025);
  const double f2 = s.trial(0.025);
  EXPECT_EQ(f1, f2);
  // A large uncommitted excursion leaves no plastic history behind.
  s.trial(-0.100);
  EXPECT_EQ(s.trial(0.025), f1);
  EXPECT_NEAR(s.committed_force(), 2.2e4, 1e-6);
}

TEST(BilinearSpring, RejectsBadParameters) {
  EXPECT_THROW(BilinearSpring({-1.0, fy, alpha}), std::invalid_argument);
  EXPECT_THROW(BilinearSpring({k0, 0.0, alpha}), std::invalid_argument);
  EXPECT_THROW(BilinearSpring({k0, fy, 1.0}), std::invalid_argument);
  EXPECT_THROW(BilinearSpring({k0, fy, -0.1}), std::invalid_argument);
  try {
    BilinearSpring({k0, -5.0, alpha});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("yield_force_n must be positive, got -5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::substructure
