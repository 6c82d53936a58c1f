// Bouc–Wen spring against closed-form monotonic solutions and its analytic bound.
//
// Under monotonic loading from z = 0 the evolution law reduces to dz/du = A − (β + γ) zⁿ:
//   n = 1:  z(u) = (A/c) (1 − e^(−c u))
//   n = 2:  z(u) = √(A/c) tanh(√(A c) u),       c = β + γ,
// and z → z_max = (A/c)^(1/n) from below.

#include "rpsd/substructure/bouc_wen_spring.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rpsd::substructure {
namespace {

constexpr double k0_n_per_m = 1.0e6, z_max = 0.01;

BoucWenSpringParameters params(double n, double beta_share, double alpha = 0.05, double A = 1.0) {
  // β + γ = A / z_maxⁿ so that z_max = 0.01 m; beta_share = β / (β + γ).
  const double c = A / std::pow(z_max, n);
  BoucWenSpringParameters p;
  p.stiffness_n_per_m = k0_n_per_m;
  p.post_yield_ratio = alpha;
  p.A = A;
  p.beta = beta_share * c;
  p.gamma = (1.0 - beta_share) * c;
  p.n = n;
  return p;
}

double z_exact(double n, double A, double c, double u) {
  if (n == 1.0) return A / c * (1.0 - std::exp(-c * u));
  return std::sqrt(A / c) * std::tanh(std::sqrt(A * c) * u);
}

TEST(BoucWen, MonotonicLoadingMatchesClosedForms) {
  for (double n : {1.0, 2.0}) {
    for (double A : {1.0, 1.5}) {
      BoucWenSpringParameters p = params(n, 0.5, 0.05, A);
      BoucWenSpring s(p);
      const double c = p.beta + p.gamma, zm = std::pow(A / c, 1.0 / n);
      EXPECT_NEAR(s.z_max_m(), zm, 1e-15);
      double max_err = 0.0;
      for (int i = 1; i <= 2000; ++i) {  // to u = 20 z_max in steps of 1 % of z_max
        const double u = i * 1e-4;
        const double f = s.trial(u);
        s.commit();
        const double z = z_exact(n, A, c, u);
        max_err = std::max(max_err, std::abs(s.committed_z_m() - z));
        EXPECT_NEAR(
            f, p.post_yield_ratio * k0_n_per_m * u + (1.0 - p.post_yield_ratio) * k0_n_per_m * s.committed_z_m(), 1e-9);
        // Tangent: α k0 + (1 − α) k0 (A − c zⁿ) on the loading branch.
        const double zc = s.committed_z_m();
        EXPECT_NEAR(
            s.tangent_stiffness(),
            p.post_yield_ratio * k0_n_per_m + (1.0 - p.post_yield_ratio) * k0_n_per_m * (A - c * std::pow(zc, n)),
            1e-6 * k0_n_per_m);
        ASSERT_LE(s.committed_z_m(), zm * (1.0 + 1e-12)) << "u = " << u;
      }
      EXPECT_LT(max_err, 1e-8 * zm) << "n = " << n << ", A = " << A;
      // Asymptote reached: at u = 20 z_max the closed forms are within 2e-9 of z_max.
      EXPECT_NEAR(s.committed_z_m(), zm, 1e-8 * zm);
    }
  }
}

TEST(BoucWen, LargeIncrementsAreSubStepped) {
  // One trial of 3 z_max from rest must match the closed form as well as fine stepping does.
  for (double n : {1.0, 2.0}) {
    BoucWenSpringParameters p = params(n, 0.5);
    BoucWenSpring s(p);
    s.trial(0.03);
    EXPECT_GT(s.last_substeps(), 1);
    EXPECT_NEAR(s.trial_z_m(), z_exact(n, 1.0, p.beta + p.gamma, 0.03), 1e-8 * z_max) << "n = " << n;
  }
}

TEST(BoucWen, InitialStiffness) {
  for (double A : {1.0, 0.8, 1.5}) {
    BoucWenSpringParameters p = params(2.0, 0.5, 0.1, A);
    BoucWenSpring s(p);
    EXPECT_DOUBLE_EQ(s.initial_stiffness(), k0_n_per_m * (0.1 + 0.9 * A));
    const double u = 1e-9 * z_max;  // z ≈ A u for u ≪ z_max
    EXPECT_NEAR(s.trial(u) / u, s.initial_stiffness(), 1e-6 * k0_n_per_m);
  }
}

TEST(BoucWen, ZStaysBoundedUnderRandomCyclicLoading) {
  struct Case {
    double n, beta_share;
  };
  // β ≥ 0 and β + γ > 0, including γ < 0 (beta_share > 1) and γ > β (beta_share < 0.5).
  for (const Case c : {Case{1.0, 0.5}, Case{2.0, 0.75}, Case{2.0, 0.2}, Case{5.0, 1.2}, Case{20.0, 0.5}}) {
    BoucWenSpring s(params(c.n, c.beta_share));
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> target(-5.0 * z_max, 5.0 * z_max);
    std::uniform_real_distribution<double> step(1e-3 * z_max, 2.0 * z_max);
    double u = 0.0, peak = 0.0;
    for (int leg = 0; leg < 40; ++leg) {
      const double goal = target(rng);
      while (u != goal) {
        const double du = std::min(step(rng), std::abs(goal - u));
        u = (goal > u) ? std::min(u + du, goal) : std::max(u - du, goal);
        s.trial(u);
        s.commit();
        peak = std::max(peak, std::abs(s.committed_z_m()));
        ASSERT_LE(std::abs(s.committed_z_m()), s.z_max_m() * (1.0 + 1e-12))
            << "n = " << c.n << ", beta share " << c.beta_share << ", u = " << u;
      }
    }
    EXPECT_GT(peak, 0.9 * s.z_max_m());  // the loading did reach the bound's neighbourhood
  }
}

// ∮ F du over cycles 0 → +um → −um → +um (the second one, after the virgin curve).
double loop_energy(BoucWenSpring& s, double um, double du) {
  double u = 0.0, f = 0.0, energy = 0.0;
  auto go = [&](double goal, bool count) {
    const int n = static_cast<int>(std::lround(std::abs(goal - u) / du));
    const double h = (goal - u) / n;
    for (int i = 1; i <= n; ++i) {
      const double u1 = u + h, f1 = s.trial(u1);
      s.commit();
      if (count) energy += 0.5 * (f + f1) * h;
      u = u1;
      f = f1;
    }
  };
  go(um, false);
  go(-um, false);
  go(um, false);
  go(-um, true);
  go(um, true);
  return energy;
}

TEST(BoucWen, LoopsDissipateAndTendToElasticPerfectlyPlasticForLargeN) {
  // With β = γ unloading is exactly elastic (dz/du = A) and, as n grows, loading becomes
  // elastic up to z_max then flat: the z-loop tends to the EPP parallelogram of area
  // 4 z_max (um − z_max), so ∮F du → (1 − α) k0 · 4 z_max (um − z_max).
  const double um = 5.0 * z_max, alpha = 0.05;
  const double epp = (1.0 - alpha) * k0_n_per_m * 4.0 * z_max * (um - z_max);
  double previous_gap = 1e300;
  for (double n : {2.0, 10.0, 50.0}) {
    BoucWenSpring s(params(n, 0.5, alpha));
    const double e = loop_energy(s, um, 1e-3 * z_max);
    EXPECT_GT(e, 0.0);
    EXPECT_LT(e, epp);  // a rounded knee always encloses less than the sharp one
    const double gap = (epp - e) / epp;
    EXPECT_LT(gap, previous_gap) << "n = " << n;
    previous_gap = gap;
  }
  EXPECT_LT(previous_gap, 0.01);  // n = 50 is within 1 % of the EPP loop
}

TEST(BoucWen, TrialsDoNotChangeTheCommittedState) {
  BoucWenSpring s(params(2.0, 0.5));
  s.trial(0.004);
  s.commit();
  const double f1 = s.trial(0.012), z1 = s.trial_z_m(), kt1 = s.tangent_stiffness();
  EXPECT_EQ(s.trial(0.012), f1);
  EXPECT_EQ(s.trial_z_m(), z1);
  EXPECT_EQ(s.tangent_stiffness(), kt1);
  s.trial(-0.05);  // large uncommitted excursion
  EXPECT_EQ(s.trial(0.012), f1);
  EXPECT_EQ(s.committed_deformation(), 0.004);
}

TEST(BoucWen, RejectsBadParameters) {
  auto bad = [](auto mutate) {
    BoucWenSpringParameters p = params(2.0, 0.5);
    mutate(p);
    EXPECT_THROW(BoucWenSpring{p}, std::invalid_argument);
  };
  bad([](BoucWenSpringParameters& p) { p.stiffness_n_per_m = 0.0; });
  bad([](BoucWenSpringParameters& p) { p.post_yield_ratio = 1.0; });
  bad([](BoucWenSpringParameters& p) { p.A = 0.0; });
  bad([](BoucWenSpringParameters& p) { p.beta = -1.0; });
  bad([](BoucWenSpringParameters& p) { p.gamma = -p.beta; });  // β + γ = 0: unbounded z
  bad([](BoucWenSpringParameters& p) { p.n = 0.5; });
  bad([](BoucWenSpringParameters& p) { p.max_substeps = 0; });
  bad([](BoucWenSpringParameters& p) { p.substep_ratio = 0.0; });
}

}  // namespace
}  // namespace rpsd::substructure
