// Damping identification against closed-form decays and growths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rpsd/studies/damping_identification.h"

namespace rpsd::studies {
namespace {

TEST(DampingIdentification, RecoversTheDampingOfAClosedFormDecay) {
  const double zeta = 0.03, omega = 2.0 * std::numbers::pi * 1.5, dt = 1.0 / 1024.0;
  const double omega_d = omega * std::sqrt(1.0 - zeta * zeta);
  std::vector<double> x;
  for (int i = 0; i < 8 * 1024; ++i) x.push_back(std::exp(-zeta * omega * i * dt) * std::cos(omega_d * i * dt));
  const IdentifiedDamping d = identify_damping(x, dt);
  EXPECT_NEAR(d.damping_ratio, zeta, 1e-5);
  EXPECT_NEAR(d.damped_frequency_hz, omega_d / (2.0 * std::numbers::pi), 1e-4);
  // A growing response gives a negative ratio.
  for (int i = 0; i < static_cast<int>(x.size()); ++i)
    x[i] = std::exp(0.02 * omega * i * dt) * std::cos(omega_d * i * dt);
  EXPECT_NEAR(identify_damping(x, dt).damping_ratio, -0.02, 1e-5);
}

}  // namespace
}  // namespace rpsd::studies
