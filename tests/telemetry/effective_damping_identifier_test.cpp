// The identified effective damping against the harmonic balance of a pure delay: a force
// f = k x(t - tau) on a sinusoidal target x = A sin(w t) is k cos(w tau) x - k sin(w tau) / w v,
// so an SDOF of mass m, damping c and numerical stiffness k_n has the damping ratio
// (c - k sin(w tau) / w) / (2 sqrt(m (k_n + k cos(w tau)))).
#include "rpsd/telemetry/effective_damping_identifier.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rpsd::telemetry {
namespace {

constexpr double kMass = 7080.0, kStiffness = 700.8e3, kDamping = 1549.0, kRate = 1024.0;

LowestMode sdof_mode(double numerical_stiffness_n_per_m, double specimen_stiffness_n_per_m) {
  LowestMode m;
  m.frequency_hz = std::sqrt((numerical_stiffness_n_per_m + specimen_stiffness_n_per_m) / kMass) / (2.0 * M_PI);
  m.numerical_stiffness_n_per_m = numerical_stiffness_n_per_m / kMass;  // phi = 1 / sqrt(m)
  m.numerical_damping_n_s_per_m = kDamping / kMass;
  m.channel_weight = {1.0 / kMass};
  return m;
}

double harmonic_balance(double k_n, double k_e, double w, double tau_s) {
  return (kDamping - k_e * std::sin(w * tau_s) / w) / (2.0 * std::sqrt(kMass * (k_n + k_e * std::cos(w * tau_s))));
}

// Feeds `steps` records of x = amplitude sin(w t), f = k_e x(t - tau) + preload.
void feed(EffectiveDampingIdentifier& id, double w, double tau_s, double k_e, std::int64_t steps,
          double preload_n = 0.0, double amplitude_m = 0.01) {
  for (std::int64_t n = 0; n < steps; ++n) {
    coordinator::StepRecord r;
    r.step = n + 1;
    r.channels = 1;
    const double t = static_cast<double>(n) / kRate;
    r.target_m[0] = amplitude_m * std::sin(w * t);
    r.specimen_restoring_force_n[0] = k_e * amplitude_m * std::sin(w * (t - tau_s)) + preload_n;
    id.observe(r);
  }
}

TEST(EffectiveDampingIdentifier, ALaggingSpecimenForceGivesTheHarmonicBalanceOfItsDelay) {
  for (const double tau_s : {0.005, 0.010, 0.020}) {
    for (const double k_n : {0.0, 300e3}) {
      const LowestMode mode = sdof_mode(k_n, kStiffness);
      const double w = 2.0 * M_PI * mode.frequency_hz;
      EffectiveDampingIdentifier id;
      id.configure(mode, kRate);
      feed(id, w, tau_s, kStiffness, 8 * 1024);
      const double expected = harmonic_balance(k_n, kStiffness, w, tau_s);
      EXPECT_LT(expected, 0.0) << "a lag this long takes more damping than the structure has";
      EXPECT_NEAR(id.damping_ratio(), expected, 1e-4 * std::abs(expected)) << tau_s << " s, k_n " << k_n;
    }
  }
}

TEST(EffectiveDampingIdentifier, ALeadReadsAsExtraDampingAndNoLagAsTheStructuresOwn) {
  const LowestMode mode = sdof_mode(0.0, kStiffness);
  const double w = 2.0 * M_PI * mode.frequency_hz;
  const double own = kDamping / (2.0 * std::sqrt(kMass * kStiffness));
  EffectiveDampingIdentifier on_time;
  on_time.configure(mode, kRate);
  feed(on_time, w, 0.0, kStiffness, 4096);
  EXPECT_NEAR(on_time.damping_ratio(), own, 1e-6);
  EffectiveDampingIdentifier lead;
  lead.configure(mode, kRate);
  feed(lead, w, -0.010, kStiffness, 4096);
  EXPECT_GT(lead.damping_ratio(), own + 0.03);
}

TEST(EffectiveDampingIdentifier, APreloadOnTheLoadCellChangesNothing) {
  const LowestMode mode = sdof_mode(0.0, kStiffness);
  const double w = 2.0 * M_PI * mode.frequency_hz;
  EffectiveDampingIdentifier plain, preloaded;
  plain.configure(mode, kRate);
  preloaded.configure(mode, kRate);
  feed(plain, w, 0.01, kStiffness, 4096);
  feed(preloaded, w, 0.01, kStiffness, 4096, 25e3);
  EXPECT_NEAR(preloaded.damping_ratio(), plain.damping_ratio(), 1e-9);
}

TEST(EffectiveDampingIdentifier, NothingUntilTwoPeriodsOfTheModeHavePassed) {
  const LowestMode mode = sdof_mode(0.0, kStiffness);
  const double w = 2.0 * M_PI * mode.frequency_hz;
  const auto two_periods = static_cast<std::int64_t>(std::ceil(2.0 * kRate / mode.frequency_hz));
  EffectiveDampingIdentifier id;
  id.configure(mode, kRate);
  feed(id, w, 0.01, kStiffness, two_periods - 1);
  EXPECT_TRUE(std::isnan(id.damping_ratio()));
  coordinator::StepRecord r;
  r.channels = 1;
  r.target_m[0] = 0.01 * std::sin(w * static_cast<double>(two_periods - 1) / kRate);
  r.specimen_restoring_force_n[0] =
      kStiffness * 0.01 * std::sin(w * (static_cast<double>(two_periods - 1) / kRate - 0.01));
  id.observe(r);
  EXPECT_TRUE(std::isfinite(id.damping_ratio()));
}

TEST(EffectiveDampingIdentifier, NothingForAnUnknownModeOrATargetThatNeverMoves) {
  EffectiveDampingIdentifier unknown;
  unknown.configure(LowestMode{}, kRate);
  feed(unknown, 10.0, 0.01, kStiffness, 4096);
  EXPECT_TRUE(std::isnan(unknown.damping_ratio()));
  EffectiveDampingIdentifier still;
  still.configure(sdof_mode(0.0, kStiffness), kRate);
  feed(still, 10.0, 0.01, kStiffness, 4096, 1e3, 0.0);
  EXPECT_TRUE(std::isnan(still.damping_ratio()));
}

}  // namespace
}  // namespace rpsd::telemetry
