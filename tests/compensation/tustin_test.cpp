// The bilinear map against its closed forms: a pole or zero p goes to z = (K + p) / (K - p),
// a strictly proper filter's zeros at infinity to z = -1, the response at w is the continuous
// one at j K tan(w dt / 2), and pre-warping makes it exact at its frequency.
#include "rpsd/compensation/tustin.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

namespace rpsd::compensation {
namespace {

// Sorted by real part, then imaginary part.
std::vector<std::complex<double>> sorted(std::vector<std::complex<double>> v) {
  std::sort(v.begin(), v.end(),
            [](auto a, auto b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return v;
}

void expect_roots(const std::vector<double>& descending, std::vector<std::complex<double>> expected, double tol) {
  const auto got = sorted(polynomial_roots(descending));
  expected = sorted(expected);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT(std::abs(got[i] - expected[i]), tol) << i;
}

std::complex<double> image(std::complex<double> p, double K) { return (K + p) / (K - p); }

TEST(Tustin, TheBenchmarksLeadLagMapsItsZeroAndPoleByTheBilinearFormula) {
  // G_T = 50.8 (s + 168.6) / (s + 8570) at 4096 Hz (Silva et al. 2020, the sample controller).
  const double dt = 1.0 / 4096.0, K = 2.0 / dt;
  const DiscreteFilterCoefficients f = tustin({{50.8, 50.8 * 168.6}, {1.0, 8570.0}}, dt);
  ASSERT_EQ(f.b.size(), 2u);
  expect_roots(f.b, {image(-168.6, K)}, 1e-12);
  expect_roots(f.a, {image(-8570.0, K)}, 1e-12);
  // The gain is kept at DC: 50.8 x 168.6 / 8570.
  EXPECT_NEAR((f.b[0] + f.b[1]) / (f.a[0] + f.a[1]), 50.8 * 168.6 / 8570.0, 1e-12);
}

TEST(Tustin, ASecondOrderLowPassHasItsPolesMappedAndItsZerosAtMinusOne) {
  const double dt = 1.0 / 1024.0, K = 2.0 / dt, w = 2.0 * std::numbers::pi * 20.0, zeta = 0.7;
  const DiscreteFilterCoefficients f = tustin({{w * w}, {1.0, 2.0 * zeta * w, w * w}}, dt);
  const std::complex<double> p(-zeta * w, w * std::sqrt(1.0 - zeta * zeta));
  expect_roots(f.a, {image(p, K), image(std::conj(p), K)}, 1e-12);
  expect_roots(f.b, {-1.0, -1.0}, 1e-6);  // a double root: found to sqrt(eps)
  EXPECT_DOUBLE_EQ(f.a[0], 1.0);
}

TEST(Tustin, TheResponseAtWIsTheContinuousOneAtTheWarpedFrequency) {
  const double dt = 1.0 / 4096.0;
  const ContinuousTransferFunction tf{{2.0, 3.0, 500.0}, {1.0, 40.0, 900.0, 2000.0}};
  const DiscreteFilterCoefficients f = tustin(tf, dt);
  for (double hz : {0.1, 5.0, 60.0, 700.0, 1900.0}) {
    const double w = 2.0 * std::numbers::pi * hz;
    const std::complex<double> expected = evaluate(tf, {0.0, 2.0 / dt * std::tan(0.5 * w * dt)});
    // Rounding of the expanded polynomials (terms of K^3 = 5.5e11 that cancel): ~1e-9 relative.
    EXPECT_LT(std::abs(discrete_response(f, w, dt) - expected), 1e-8 * std::abs(expected)) << hz;
  }
}

TEST(Tustin, PreWarpingMakesTheFilterExactAtItsFrequency) {
  const double dt = 1.0 / 256.0, hz = 40.0, w = 2.0 * std::numbers::pi * hz;
  const ContinuousTransferFunction tf{{1.0, 0.0}, {1.0, 2.0 * 0.05 * w, w * w}};  // a resonance at 40 Hz
  const std::complex<double> exact = evaluate(tf, {0.0, w});
  EXPECT_LT(std::abs(discrete_response(tustin(tf, dt, hz), w, dt) - exact), 1e-9 * std::abs(exact));
  // Plain Tustin misses it: the resonance moves to a lower frequency.
  EXPECT_GT(std::abs(discrete_response(tustin(tf, dt), w, dt) - exact), 0.1 * std::abs(exact));
}

TEST(Tustin, RefusesWhatIsNotAProperFilter) {
  EXPECT_THAT(
      [] {
        (void)tustin({{1.0, 0.0, 0.0}, {1.0, 1.0}}, 0.001);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("not proper")));
  EXPECT_THAT(
      [] {
        (void)tustin({{1.0}, {0.0, 1.0}}, 0.001);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("leading coefficient is zero")));
  EXPECT_THAT(
      [] {
        (void)tustin({{1.0}, {1.0, 1.0}}, 0.001, 600.0);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("below Nyquist")));
}

}  // namespace
}  // namespace rpsd::compensation
