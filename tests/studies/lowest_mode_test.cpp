// The identified effective damping of a whole test (the telemetry's, issue 31) against the
// delay theory's exact root: the seed paper's SDOF whose specimen follows an ideal actuator
// tau late, m x'' + c x' + k x(t - tau) = 0, identified from its record as it runs.
#include "rpsd/studies/lowest_mode.h"

#include <gtest/gtest.h>

#include <cmath>

#include "rpsd/compensation/delay_theory.h"
#include "rpsd/coordinator/record_observer.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/specimen_sdof.h"

namespace rpsd::studies {
namespace {

struct Identifying final : coordinator::RecordObserver {
  telemetry::EffectiveDampingIdentifier identifier;
  void observe(const coordinator::StepRecord& r) override { identifier.observe(r); }
};

TEST(LowestModeForIdentification, TheSdofsModeWithItsChannelWeight) {
  hybrid_test::SpecimenSdof s;
  const telemetry::LowestMode mode = lowest_mode_for_identification(hybrid_test::specimen_sdof_test(s));
  ASSERT_TRUE(mode.known());
  EXPECT_NEAR(mode.frequency_hz, std::sqrt(s.stiffness_n_per_m / s.mass_kg) / (2.0 * M_PI), 1e-9);
  ASSERT_EQ(mode.channel_weight.size(), 1u);
  EXPECT_NEAR(mode.channel_weight[0], 1.0 / s.mass_kg, 1e-12);
  EXPECT_NEAR(mode.numerical_stiffness_n_per_m, 0.0, 1e-9);  // the whole spring is the specimen's
  EXPECT_NEAR(mode.numerical_damping_n_s_per_m,
              2.0 * s.damping_ratio * std::sqrt(s.stiffness_n_per_m * s.mass_kg) / s.mass_kg, 1e-9);
}

TEST(LowestModeForIdentification, ATestsIdentifiedDampingIsTheDelayTheorysExactRoot) {
  for (const double tau_s : {0.0, 0.005, 0.010}) {
    hybrid_test::SpecimenSdof s;
    s.duration_s = 4.0;
    s.plant = servo::PureDelayParameters{tau_s, s.stiffness_n_per_m, 8192.0, {}, {}};
    const hybrid_test::TestConfig config = hybrid_test::specimen_sdof_test(s);
    Identifying watch;
    watch.identifier.configure(lowest_mode_for_identification(config), config.control_rate_hz);
    {
      hybrid_test::TestAssembly test(config, {{}, false, false, {}, nullptr, {&watch}});
      ASSERT_EQ(test.run({}, {}), coordinator::StepOutcome::kOk);
      test.finish(coordinator::StepOutcome::kOk);
    }
    const double c = 2.0 * s.damping_ratio * std::sqrt(s.stiffness_n_per_m * s.mass_kg);
    const double exact =
        compensation::damping_ratio_of(compensation::dominant_root({s.mass_kg, c, 0.0, s.stiffness_n_per_m}, tau_s));
    EXPECT_NEAR(watch.identifier.damping_ratio(), exact, 0.001) << tau_s * 1e3 << " ms";
  }
}

}  // namespace
}  // namespace rpsd::studies
