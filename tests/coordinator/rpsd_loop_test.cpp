// The RPsD loop against delay theory: an ideal pure-delay actuator must give the damping of
// the exact DDE root, and perfect compensation must track the target to the extrapolation error.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "rpsd/compensation/delay_theory.h"
#include "rpsd/compensation/polynomial_extrapolation.h"
#include "rpsd/studies/damping_identification.h"
#include "specimen_runs.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

using studies::IdentifiedDamping;
using studies::identify_damping;
using testing::displacements;
using testing::run_sdof;

servo::PureDelayParameters delay_plant(double delay_s) {
  return {delay_s, SpecimenSdof{}.stiffness_n_per_m, 8192.0, {}};
}

compensation::DelayedOscillator paper_sdof(const SpecimenSdof& s) {
  return {s.mass_kg, 2.0 * s.damping_ratio * std::sqrt(s.stiffness_n_per_m * s.mass_kg), 0.0, s.stiffness_n_per_m};
}

TEST(RpsdLoop, UndercompensatedDelayGivesTheDampingOfTheExactDdeRoot) {
  SpecimenSdof setup;  // the paper's elastic SDOF: 7080 kg, 700.8 kN/m, 1.1 %
  setup.duration_s = 12.0;
  for (double delay_s : {0.0, 0.002, 0.005, 0.010}) {
    setup.plant = delay_plant(delay_s);
    const auto r = run_sdof(setup);
    ASSERT_EQ(r.outcome, StepOutcome::kOk);
    const IdentifiedDamping identified = identify_damping(displacements(r), (1.0 / setup.control_rate_hz), 0.0, 1e-6);
    const double exact = compensation::damping_ratio_of(compensation::dominant_root(paper_sdof(setup), delay_s));
    EXPECT_NEAR(identified.damping_ratio, exact, 0.001) << delay_s * 1e3 << " ms";
    RecordProperty("delay_" + std::to_string(static_cast<int>(delay_s * 1e3)) + "ms",
                   std::to_string(identified.damping_ratio) + " identified, " + std::to_string(exact) + " exact");
  }
}

TEST(RpsdLoop, PerfectCompensationTracksTheTargetToTheExtrapolationError) {
  SpecimenSdof setup;
  setup.duration_s = 4.0;
  const double delay_s = 0.020;
  for (int order : {2, 3}) {
    setup.compensation = compensation::PolynomialExtrapolationParameters{order, delay_s};
    setup.plant = delay_plant(delay_s);
    const auto r = run_sdof(setup);
    ASSERT_EQ(r.outcome, StepOutcome::kOk);
    // For a sinusoid of the structure's frequency, measured / target = H(e^{j w dt}) e^{-j w tau}.
    const double omega = std::sqrt(setup.stiffness_n_per_m / setup.mass_kg);
    const double bound = std::abs(compensation::extrapolation_response(order, delay_s / (1.0 / setup.control_rate_hz),
                                                                       omega * (1.0 / setup.control_rate_hz)) *
                                      std::exp(std::complex<double>(0.0, -omega * delay_s)) -
                                  1.0);
    double worst = 0.0, peak = 0.0;
    // After the delay line has filled with the test's own commands.
    for (const auto& s : r.records) {
      if (s.time_s < 0.5) continue;
      worst = std::max(worst, std::abs(s.measured_m[0] - s.target_m[0]));
      peak = std::max(peak, std::abs(s.target_m[0]));
    }
    EXPECT_LT(worst / peak, 1.5 * bound) << "order " << order;
    // ...and the damping is the structure's own, not the delay's.
    const IdentifiedDamping identified = identify_damping(displacements(r), (1.0 / setup.control_rate_hz), 0.5, 1e-6);
    EXPECT_NEAR(identified.damping_ratio, setup.damping_ratio, 0.002) << "order " << order;
  }
}

TEST(RpsdLoop, AsFastAsPossibleRunsAreBitForBitRepeatable) {
  SpecimenSdof setup;
  setup.duration_s = 1.0;
  setup.plant = delay_plant(0.01);
  const auto ra = run_sdof(setup), rb = run_sdof(setup);
  ASSERT_EQ(ra.records.size(), rb.records.size());
  for (std::size_t i = 0; i < ra.records.size(); ++i) {
    ASSERT_EQ(ra.records[i].measured_m[0], rb.records[i].measured_m[0]);
    ASSERT_EQ(ra.records[i].displacement_m[0], rb.records[i].displacement_m[0]);
  }
}

TEST(RpsdLoop, EnergyBalanceCloses) {
  // Input energy = kinetic energy + damping energy + restoring work, to discretisation error.
  SpecimenSdof setup;
  setup.duration_s = 3.0;
  const auto r = run_sdof(setup);
  const double strain0 = 0.5 * setup.stiffness_n_per_m * setup.initial_displacement_m * setup.initial_displacement_m;
  for (const auto& s : r.records) {
    const double error = s.input_energy_j - (s.kinetic_energy_j + s.damping_energy_j + s.restoring_energy_j);
    ASSERT_NEAR(error, 0.0, 1e-3 * strain0) << s.time_s;
  }
}

TEST(RpsdLoop, GroundMotionResponseMatchesTheClosedForm) {
  // A perfect actuator (no delay) turns RPsD into plain integration: a harmonic ground
  // acceleration from rest must give the closed-form transient plus steady state.
  SpecimenSdof setup;
  setup.initial_displacement_m = 0.0;
  const double amplitude = 1.0, omega_g = 2.0 * std::numbers::pi * 1.2, dt = (1.0 / setup.control_rate_hz);
  for (int n = 0; n <= 4 * 1024; ++n)
    setup.ground_acceleration_m_per_s2.push_back(amplitude * std::sin(omega_g * n * dt));
  const auto r = run_sdof(setup);
  ASSERT_EQ(r.records.size(), 4u * 1024u);  // the test ends with the record

  const double m = setup.mass_kg, k = setup.stiffness_n_per_m, omega = std::sqrt(k / m), zeta = setup.damping_ratio;
  const double c = 2.0 * zeta * omega * m, omega_d = omega * std::sqrt(1.0 - zeta * zeta);
  const std::complex<double> h = -m * amplitude / std::complex<double>(k - m * omega_g * omega_g, c * omega_g);
  const auto particular = [&](double t) { return (h * std::exp(std::complex<double>(0.0, omega_g * t))).imag(); };
  const auto particular_rate = [&](double t) {
    return (h * std::complex<double>(0.0, omega_g) * std::exp(std::complex<double>(0.0, omega_g * t))).imag();
  };
  const double c1 = -particular(0.0), c2 = (-particular_rate(0.0) + zeta * omega * c1) / omega_d;
  double worst = 0.0, peak = 0.0;
  for (const auto& s : r.records) {
    const double t = s.time_s;
    const double exact =
        particular(t) + std::exp(-zeta * omega * t) * (c1 * std::cos(omega_d * t) + c2 * std::sin(omega_d * t));
    worst = std::max(worst, std::abs(s.displacement_m[0] - exact));
    peak = std::max(peak, std::abs(exact));
  }
  EXPECT_LT(worst / peak, 2e-3);
}

TEST(RpsdLoop, MeasuredForcePathEqualsStiffnessPathWhenTheLoadCellReadsKx) {
  // An ideal plant whose load cell reads k x_m: both restoring-force paths see the same
  // numbers, so the two tests must agree to the last bit.
  SpecimenSdof setup;
  setup.duration_s = 2.0;
  setup.plant = delay_plant(0.004);
  const auto by_stiffness = run_sdof(setup);
  setup.restoring_force = RestoringForceSource::kMeasuredForce;
  const auto by_force = run_sdof(setup);
  ASSERT_EQ(by_stiffness.records.size(), by_force.records.size());
  for (std::size_t i = 0; i < by_force.records.size(); ++i) {
    ASSERT_EQ(by_stiffness.records[i].displacement_m[0], by_force.records[i].displacement_m[0]) << i;
    ASSERT_EQ(by_force.records[i].specimen_restoring_force_n[0], by_force.records[i].measured_force_n[0]);
  }
}

}  // namespace
}  // namespace rpsd::coordinator
