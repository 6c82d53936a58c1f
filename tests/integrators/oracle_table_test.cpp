// Section 1 of the reference sheet: spectral radius, period ratio and numerical damping
// (xi = 0) from the eigenvalues of the amplification matrix built by stepping the code.
#include "rpsd/integrators/amplification.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace rpsd::integrators::test {
namespace {

struct Cell {
  double omega_dt, rho, period_ratio, xi_bar;
};
struct Row {
  std::string name;
  std::vector<IntegratorConfig> configs;
  std::vector<Cell> cells;
};

std::vector<Row> oracle() {
  return {
      {"CD", {CentralDifferenceParameters{}}, {{0.5, 1, 0.9894, 0}, {1, 1, 0.9549, 0}}},
      {"avg-acc = CR = Chang",
       {NewmarkParameters::average_acceleration(), ChenRiclesParameters{}, ChangParameters{}},
       {{0.5, 1, 1.0205, 0}, {1, 1, 1.0784, 0}, {3, 1, 1.5263, 0}, {10, 1, 3.6406, 0}}},
      {"HHT -0.1 = alpha-OS -0.1",
       {HhtAlphaParameters{-0.1, {}}, AlphaOsParameters{-0.1}},
       {{0.5, .9994, 1.0254, .0011}, {1, .9938, 1.0945, .0068}, {3, .9260, 1.5785, .0405}, {10, .8378, 3.7082, .0656}}},
      {"GA = KR rho 0.8",
       {GeneralizedAlphaParameters{0.8, {}}, KolayRiclesAlphaParameters{0.8}},
       {{0.5, 1.0, 1.0216, .0001}, {1, .9995, 1.0826, .0006}, {3, .9873, 1.5510, .0066}, {10, .9298, 3.7358, .0272}}},
      {"GA = KR rho 0.5 = HHT -1/3",
       {GeneralizedAlphaParameters{0.5, {}}, KolayRiclesAlphaParameters{0.5}, HhtAlphaParameters{-1.0 / 3.0, {}},
        AlphaOsParameters{-1.0 / 3.0}},
       {{0.5, .9990, 1.0301, .0020}, {1, .9893, 1.1105, .0119}, {3, .8761, 1.6511, .0728}, {10, .6825, 3.9355, .1503}}},
      {"GA = KR rho 0",
       {GeneralizedAlphaParameters{0.0, {}}, KolayRiclesAlphaParameters{0.0}},
       {{0.5, .9842, 1.0858, .0345}, {1, .9066, 1.2474, .1224}, {3, .5618, 2.1097, .4054}, {10, .2425, 5.5073, .7802}}},
  };
}

TEST(OracleTable, SpectralRadiusPeriodRatioAndDampingTo1e3) {
  for (const auto& row : oracle())
    for (const auto& config : row.configs)
      for (const auto& c : row.cells) {
        const auto p = analyze_amplification(config, c.omega_dt, 0.0);
        const std::string where =
            row.name + " [" + std::string(integrator_name(config)) + "] Omega=" + std::to_string(c.omega_dt);
        EXPECT_NEAR(p.spectral_radius, c.rho, 1e-3) << where;
        ASSERT_TRUE(p.oscillatory) << where;
        EXPECT_NEAR(p.period_ratio, c.period_ratio, 1e-3) << where;
        EXPECT_NEAR(p.numerical_damping_ratio, c.xi_bar, 1e-3) << where;
      }
}

TEST(OracleTable, CentralDifferenceUnstableAtOmega3) {
  EXPECT_NEAR(analyze_amplification(CentralDifferenceParameters{}, 3.0, 0.0).spectral_radius, 6.854, 1e-3);
}

// Closed forms from the sheet: CD T/T = Omega/(2 asin(Omega/2)); average acceleration
// T/T = Omega/(2 atan(Omega/2)) and lambda = 0.6 +- 0.8 i at Omega = 1; rho_inf.
TEST(OracleTable, ClosedForms) {
  for (double w : {0.1, 0.7, 1.5, 1.9}) {
    const auto p = analyze_amplification(CentralDifferenceParameters{}, w, 0.0);
    EXPECT_NEAR(p.period_ratio, w / (2 * std::asin(w / 2)), 1e-9);
    EXPECT_NEAR(p.spectral_radius, 1.0, 1e-9);
  }
  for (const IntegratorConfig& c : {IntegratorConfig{NewmarkParameters::average_acceleration()},
                                    IntegratorConfig{ChenRiclesParameters{}}, IntegratorConfig{ChangParameters{}}}) {
    for (double w : {0.1, 1.0, 5.0, 50.0}) {
      const auto p = analyze_amplification(c, w, 0.0);
      EXPECT_NEAR(p.period_ratio, w / (2 * std::atan(w / 2)), 1e-8 * w);
    }
    const auto p = analyze_amplification(c, 1.0, 0.0);
    bool found = false;
    for (const auto& l : p.eigenvalues)
      if (std::abs(l - std::complex<double>(0.6, 0.8)) < 1e-12) found = true;
    EXPECT_TRUE(found) << integrator_name(c);
  }
  // rho_inf: the spectral radius tends to it as Omega -> infinity (slowly: about 2e-3 away
  // at Omega = 1e4 for rho_inf = 0).
  EXPECT_NEAR(analyze_amplification(HhtAlphaParameters{-0.1, {}}, 1e4, 0.0).spectral_radius, 0.9 / 1.1, 3e-3);
  for (double rho : {0.0, 0.3, 0.8, 1.0}) {
    EXPECT_NEAR(analyze_amplification(GeneralizedAlphaParameters{rho, {}}, 1e4, 0.0).spectral_radius, rho, 3e-3);
    EXPECT_NEAR(analyze_amplification(KolayRiclesAlphaParameters{rho}, 1e4, 0.0).spectral_radius, rho, 3e-3);
  }
}

// With physical damping (treated implicitly in velocity) the CD limit stays 2, and the
// eigenvalue damping of average acceleration at small Omega approaches the physical xi.
TEST(OracleTable, DampedCases) {
  for (double xi : {0.05, 0.2})
    EXPECT_NEAR(numerical_stability_limit(CentralDifferenceParameters{}, xi, 10.0), 2.0, 1e-6);
  const auto p = analyze_amplification(NewmarkParameters::average_acceleration(), 0.01, 0.05);
  EXPECT_NEAR(p.numerical_damping_ratio, 0.05 / std::sqrt(1.0 - 0.05 * 0.05), 1e-5);
  EXPECT_NEAR(p.algorithmic_damping_ratio, 0.0, 1e-5);
  EXPECT_NEAR(p.period_ratio, 1.0 / std::sqrt(1.0 - 0.05 * 0.05), 1e-5);
}

}  // namespace
}  // namespace rpsd::integrators::test
