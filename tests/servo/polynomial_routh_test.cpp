#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rpsd/servo/polynomial.h"
#include "rpsd/servo/routh.h"

namespace rpsd::servo {
namespace {

TEST(Polynomial, ProductAndRootsOfKnownFactors) {
  // (s + 1)(s + 2)(s + 3) = s^3 + 6 s^2 + 11 s + 6
  const Polynomial p = Polynomial{1, 1} * Polynomial{2, 1} * Polynomial{3, 1};
  EXPECT_EQ(p.degree(), 3);
  EXPECT_DOUBLE_EQ(p.coefficient(0), 6.0);
  EXPECT_DOUBLE_EQ(p.coefficient(1), 11.0);
  EXPECT_DOUBLE_EQ(p.coefficient(2), 6.0);
  auto roots = p.roots();
  std::vector<double> real;
  for (auto r : roots) real.push_back(r.real());
  std::sort(real.begin(), real.end());
  EXPECT_NEAR(real[0], -3.0, 1e-12);
  EXPECT_NEAR(real[1], -2.0, 1e-12);
  EXPECT_NEAR(real[2], -1.0, 1e-12);
}

TEST(Polynomial, EvaluatesAtComplexPoint) {
  const Polynomial p{1.0, 0.0, 1.0};  // 1 + s^2 vanishes at s = i
  EXPECT_NEAR(std::abs(p(std::complex<double>(0.0, 1.0))), 0.0, 1e-15);
  EXPECT_NEAR(p(std::complex<double>(2.0, 0.0)).real(), 5.0, 1e-15);
}

TEST(Routh, ClassifiesKnownPolynomials) {
  EXPECT_TRUE(routh_hurwitz_stable(Polynomial{6, 11, 6, 1}));
  // s^3 + s^2 + 2 s + 8: a2 a1 = 2 < a3 a0 = 8, two roots in the right half plane.
  EXPECT_FALSE(routh_hurwitz_stable(Polynomial{8, 2, 1, 1}));
  EXPECT_FALSE(routh_hurwitz_stable(Polynomial{-1, 1}));    // root at +1
  EXPECT_FALSE(routh_hurwitz_stable(Polynomial{1, 0, 1}));  // marginal: +/- i
  // Fifth order with roots -1, -2, -3, -1 +/- 2i.
  const Polynomial stable5 = Polynomial{1, 1} * Polynomial{2, 1} * Polynomial{3, 1} * Polynomial{5, 2, 1};
  EXPECT_TRUE(routh_hurwitz_stable(stable5));
  // Roots 0.5 +/- 2i make it unstable.
  const Polynomial unstable5 = Polynomial{1, 1} * Polynomial{2, 1} * Polynomial{3, 1} * Polynomial{4.25, -1, 1};
  EXPECT_FALSE(routh_hurwitz_stable(unstable5));
}

TEST(Routh, LargestGainOfCubicMatchesClosedForm) {
  // s^3 + a s^2 + b s + K is stable iff a b > K.
  const double a = 3.0, b = 7.0;
  const double gain = largest_stable_gain(
      [&](double k) {
        return routh_hurwitz_stable(Polynomial{k, b, a, 1.0});
      },
      1e3);
  EXPECT_NEAR(gain, a * b, 1e-6);
}

}  // namespace
}  // namespace rpsd::servo
