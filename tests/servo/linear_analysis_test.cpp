// The linear analysis against the seed paper's reported figures and against independent
// derivations of the same quantity (closed form vs Routh vs eigenvalues of the simulation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "paper_rig.h"
#include "rpsd/servo/linear_analysis.h"

namespace rpsd::servo {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

TEST(PaperRig, ReproducesThePapersReportedFigures) {
  const auto p = testing::paper_rig();
  const ServoAnalysis a = analyze(p);
  EXPECT_NEAR(a.cutoff_frequency_hz, 1.96, 0.005);            // Eq. 9, paper: 1.96 Hz
  EXPECT_NEAR(a.response_delay_ms, 81.0, 0.5);                // Eq. 12, paper: 81 ms
  EXPECT_NEAR(a.amplitude_reduction_at_2hz, 0.30, 0.005);     // Eq. 10, paper: ~30 % at 2 Hz
  EXPECT_NEAR(a.specimen_natural_frequency_hz, 1.58, 0.005);  // paper: 1.58 Hz
  // The operating gain is stable, as the paper's tests were.
  EXPECT_LT(a.p_gain, a.max_stable_p_gain);
  EXPECT_LT(a.p_gain, a.max_stable_p_gain_full_model);
}

TEST(PaperRig, AmplitudeReductionIsOneMinusFirstOrderMagnitude) {
  const auto p = testing::paper_rig();
  const TransferFunction first_order = first_order_approximation(p);
  for (double f : {0.5, 1.0, 2.0, 5.0, 10.0}) {
    EXPECT_NEAR(amplitude_reduction(p, f), 1.0 - std::abs(first_order.at_frequency_hz(f)), 1e-12) << f;
  }
}

TEST(PaperRig, Eq8LowFrequencyDelayIsTheFirstOrderDelay) {
  // The paper neglects the first denominator term of Eq. 8 near the specimen frequency; the
  // phase delay of the full Eq. 8 at low frequency must then be close to T_d = 1/omega_c.
  const auto p = testing::paper_rig();
  const TransferFunction g = command_to_displacement(p, LinearModel::kPaperEq8);
  const double f = 0.05;
  const double delay_s = -std::arg(g.at_frequency_hz(f)) / (kTwoPi * f);
  EXPECT_NEAR(delay_s, response_delay_s(p), 0.02 * response_delay_s(p));
}

TEST(PaperRig, OilColumnIsTheLightlyDampedRootPairOfEq8) {
  const auto p = testing::paper_rig();
  const Eigen::VectorXcd roots = command_to_displacement(p, LinearModel::kPaperEq8).denominator.roots();
  const auto oscillatory = *std::max_element(roots.begin(), roots.end(),
                                             [](auto a, auto b) { return std::abs(a.imag()) < std::abs(b.imag()); });
  const double eq11 = oil_column_frequency_rad_s(p);
  EXPECT_NEAR(std::abs(oscillatory), eq11, 0.02 * eq11);
  EXPECT_LT(-oscillatory.real() / std::abs(oscillatory), 0.1);  // "slightly damped"
}

TEST(PaperRig, RouthClosedFormMatchesRouthArrayBisection) {
  const auto p = testing::paper_rig();
  EXPECT_NEAR(max_stable_p_gain(p, LinearModel::kPaperEq8), max_stable_p_gain_closed_form(p),
              1e-7 * max_stable_p_gain_closed_form(p));
}

TEST(PaperRig, SimulationJacobianHasTheRootsOfTheFullTransferFunction) {
  // Two independent routes to the same dynamics: the polynomial algebra of Eq. 8 with the
  // servovalve of Eq. 2, and the Jacobian of the time-domain model the simulation integrates.
  const auto p = testing::paper_rig();
  Eigen::VectorXcd from_polynomial = command_to_displacement(p, LinearModel::kFullLinear).denominator.roots();
  Eigen::VectorXcd from_jacobian = balanced_eigenvalues(linearised_state_matrix(p));
  ASSERT_EQ(from_polynomial.size(), from_jacobian.size());
  const auto order = [](std::complex<double> a, std::complex<double> b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  };
  std::sort(from_polynomial.begin(), from_polynomial.end(), order);
  std::sort(from_jacobian.begin(), from_jacobian.end(), order);
  for (Eigen::Index i = 0; i < from_jacobian.size(); ++i) {
    EXPECT_NEAR(std::abs(from_polynomial[i] - from_jacobian[i]), 0.0, 1e-6 * std::abs(from_jacobian[i])) << i;
  }
}

TEST(PaperRig, EigenvalueGainLimitMatchesRouthOnTheFullModel) {
  const auto p = testing::paper_rig();
  const double routh = max_stable_p_gain(p, LinearModel::kFullLinear);
  EXPECT_NEAR(max_stable_p_gain_from_eigenvalues(p), routh, 1e-5 * routh);
}

TEST(Figure7, MaximumGainFallsWithAttachedMass) {
  const auto p = testing::paper_rig();
  double previous = std::numeric_limits<double>::infinity();
  for (double mass : {50.0, 200.0, 1000.0, 3000.0, 7080.0, 15000.0, 30000.0}) {
    const auto q = with_attached_mass(p, mass);
    EXPECT_DOUBLE_EQ(q.specimen.damping_n_s_per_m(), p.specimen.damping_n_s_per_m());
    const double gain = max_stable_p_gain(q, LinearModel::kPaperEq8);
    EXPECT_LT(gain, previous) << mass;
    previous = gain;
  }
  // Light masses allow far larger gains than the paper's 7080 kg (the damper's c/m term)...
  EXPECT_GT(max_stable_p_gain(with_attached_mass(p, 1.0), LinearModel::kPaperEq8),
            20.0 * max_stable_p_gain(p, LinearModel::kPaperEq8));
  // ...and heavy ones approach the leakage-limited floor C_l (A^2 + C_l c) / (K_a A K_v C_F K_s),
  // the m -> infinity limit of the Routh condition.
  const double cl = p.actuator.leakage_m3_per_s_per_pa, area = p.actuator.piston_area_m2;
  const double floor = cl * (area * area + cl * p.specimen.damping_n_s_per_m()) /
                       (p.actuator.compressibility_m5_per_n() * area * p.flow.no_load_flow_gain_m3_per_s *
                        p.sensors.lvdt_gain_v_per_m * p.servovalve.static_gain_per_v());
  EXPECT_NEAR(max_stable_p_gain(with_attached_mass(p, 1e9), LinearModel::kPaperEq8), floor, 1e-3 * floor);
}

}  // namespace
}  // namespace rpsd::servo
