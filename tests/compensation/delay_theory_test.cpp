// Delay theory against the reference sheet's exact roots and critical delays (section 3).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rpsd/compensation/delay_theory.h"

namespace rpsd::compensation {
namespace {

// omega_n = 2 pi (1 Hz), unit mass, a share of the stiffness acting through the delay.
DelayedOscillator oscillator(double zeta, double experimental_share = 1.0) {
  const double omega = 2.0 * std::numbers::pi, k = omega * omega;
  return {1.0, 2.0 * zeta * omega, (1.0 - experimental_share) * k, experimental_share * k};
}

TEST(DelayTheory, ExactRootsMatchTheSheet) {
  EXPECT_NEAR(damping_ratio_of(dominant_root(oscillator(0.05), 0.005)), 0.03429, 5e-6);
  EXPECT_NEAR(damping_ratio_of(dominant_root(oscillator(0.05), 0.010)), 0.01859, 5e-6);
  EXPECT_NEAR(damping_ratio_of(dominant_root(oscillator(0.02), 0.010)), -0.01138, 5e-6);
}

TEST(DelayTheory, ApproximationMatchesTheSheet) {
  EXPECT_NEAR(approximate_damping_ratio(oscillator(0.05), 0.005), 0.03429, 5e-6);
  EXPECT_NEAR(approximate_damping_ratio(oscillator(0.05), 0.010), 0.01858, 5e-6);
  EXPECT_NEAR(approximate_damping_ratio(oscillator(0.02), 0.010), -0.01142, 5e-6);
}

TEST(DelayTheory, CriticalDelaysMatchTheSheet) {
  EXPECT_NEAR(critical_delay_s(oscillator(0.05)), 15.942e-3, 5e-7);
  EXPECT_NEAR(critical_delay_s(oscillator(0.02)), 6.368e-3, 5e-7);
  EXPECT_NEAR(critical_delay_s(oscillator(0.05, 0.5)), 32.045e-3, 5e-7);
  EXPECT_NEAR(critical_delay_s(oscillator(0.05, 0.25)), 65.455e-3, 5e-7);
  // At the critical delay the exact root sits on the imaginary axis.
  const double tau = critical_delay_s(oscillator(0.05));
  EXPECT_NEAR(dominant_root(oscillator(0.05), tau).real(), 0.0, 1e-9);
}

TEST(DelayTheory, LeadAddsDamping) {
  EXPECT_GT(damping_ratio_of(dominant_root(oscillator(0.011), -0.02)), 0.011);
  EXPECT_NEAR(damping_ratio_of(dominant_root(oscillator(0.011), 0.0)), 0.011, 1e-12);
}

TEST(DelayTheory, StableForEveryDelayWhenTheExperimentalPartIsSmall) {
  // k_e^2 < c^2 k_n / m - c^4 / (4 m^2): no crossing exists.
  EXPECT_TRUE(std::isinf(critical_delay_s(oscillator(0.3, 0.05))));
}

}  // namespace
}  // namespace rpsd::compensation
