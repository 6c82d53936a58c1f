// Horiuchi's polynomial extrapolation against the reference sheet's table and frequency
// responses, and against the Lagrange remainder on an ideal delay plant.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <numbers>

#include "rpsd/compensation/polynomial_extrapolation.h"
#include "test_signals.h"

namespace rpsd::compensation {
namespace {

TEST(PolynomialExtrapolation, CoefficientsMatchTheTable) {
  const auto p0 = extrapolation_coefficients(0, 1.0);
  EXPECT_DOUBLE_EQ(p0[0], 1.0);
  const auto p1 = extrapolation_coefficients(1, 1.0);
  EXPECT_DOUBLE_EQ(p1[0], 2.0);
  EXPECT_DOUBLE_EQ(p1[1], -1.0);
  const auto p2 = extrapolation_coefficients(2, 1.0);
  EXPECT_DOUBLE_EQ(p2[0], 3.0);
  EXPECT_DOUBLE_EQ(p2[1], -3.0);
  EXPECT_DOUBLE_EQ(p2[2], 1.0);
  const auto p3 = extrapolation_coefficients(3, 1.0);
  EXPECT_DOUBLE_EQ(p3[0], 4.0);
  EXPECT_DOUBLE_EQ(p3[1], -6.0);
  EXPECT_DOUBLE_EQ(p3[2], 4.0);
  EXPECT_DOUBLE_EQ(p3[3], -1.0);
  const auto half = extrapolation_coefficients(3, 0.5);
  EXPECT_DOUBLE_EQ(half[0], 2.1875);
  EXPECT_DOUBLE_EQ(half[1], -2.1875);
  EXPECT_DOUBLE_EQ(half[2], 1.3125);
  EXPECT_DOUBLE_EQ(half[3], -0.3125);
}

TEST(PolynomialExtrapolation, CoefficientsSumToOneAndReproducePolynomialsExactly) {
  // Lagrange weights: exact for every polynomial of degree <= p, at any alpha.
  for (int p = 0; p <= 3; ++p) {
    for (double alpha : {0.0, 0.37, 1.0, 2.5, 7.25}) {
      const auto c = extrapolation_coefficients(p, alpha);
      for (int degree = 0; degree <= p; ++degree) {
        double extrapolated = 0.0;
        for (int j = 0; j <= p; ++j) extrapolated += c[static_cast<std::size_t>(j)] * std::pow(-j, degree);
        EXPECT_NEAR(extrapolated, std::pow(alpha, degree), 1e-9 * std::pow(1.0 + alpha, degree))
            << "p " << p << " alpha " << alpha << " degree " << degree;
      }
    }
  }
}

TEST(PolynomialExtrapolation, FrequencyResponseMatchesTheSheet) {
  const std::complex<double> h2 = extrapolation_response(2, 1.0, 0.5);
  EXPECT_NEAR(std::abs(h2), 1.0862, 5e-5);
  EXPECT_NEAR(std::arg(h2), 0.5817, 5e-5);
  const std::complex<double> h3 = extrapolation_response(3, 1.0, 0.5);
  EXPECT_NEAR(std::abs(h3), 0.9689, 5e-5);
  EXPECT_NEAR(std::arg(h3), 0.5521, 5e-5);
}

TEST(PolynomialExtrapolation, SimulatedResponseEqualsTheClosedForm) {
  const double dt = 1.0 / 1024.0;
  for (int p = 0; p <= 3; ++p) {
    PolynomialExtrapolationCompensator c({p, 1.7 * dt});
    c.configure(dt);
    EXPECT_NEAR(c.alpha(), 1.7, 1e-12);
    for (double theta : {0.01, 0.5, 2.0}) {
      const auto measured = testing::simulated_response(c, theta, 50);
      EXPECT_NEAR(std::abs(measured - extrapolation_response(p, 1.7, theta)), 0.0, 1e-12)
          << "p " << p << " w dt " << theta;
    }
  }
}

// A pure delay of m control steps behind the command; with alpha = m the extrapolator's
// error on a sinusoid is bounded by the Lagrange remainder
//   X w^(p+1) / (p+1)! * prod_{k=0..p} (alpha + k) dt^(p+1),
// and over a cycle it comes within a few per cent of it.
TEST(PolynomialExtrapolation, IdealDelayPlantTracksWithinTheLagrangeRemainder) {
  const double dt = 1.0 / 1024.0;
  const int m = 20;  // 19.5 ms
  const double X = 0.01, w = 2.0 * std::numbers::pi * 1.5;
  for (int p = 1; p <= 3; ++p) {
    PolynomialExtrapolationCompensator c({p, m * dt});
    c.configure(dt);
    c.reset(0.0);
    std::deque<double> line(static_cast<std::size_t>(m), 0.0);  // the plant's delay line
    double worst = 0.0;
    for (int n = 0; n < 4096; ++n) {
      const double target = X * std::sin(w * n * dt);
      line.push_back(c.command(target));
      const double measured = line.front();
      line.pop_front();
      if (n > 2 * m) worst = std::max(worst, std::abs(measured - target));
    }
    double bound = X * std::pow(w * dt, p + 1) / std::tgamma(p + 2.0);
    for (int k = 0; k <= p; ++k) bound *= (m + k);
    testing::record("error_over_bound_order_" + std::to_string(p), worst / bound);
    EXPECT_LE(worst, bound) << "order " << p;
    EXPECT_GE(worst, 0.85 * bound) << "order " << p;
  }
}

TEST(PolynomialExtrapolation, RejectsOrderOutOfRangeAndNegativeDelay) {
  try {
    PolynomialExtrapolationCompensator c({4, 0.01});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("order"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("got 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PolynomialExtrapolationCompensator({2, -0.01}), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::compensation
