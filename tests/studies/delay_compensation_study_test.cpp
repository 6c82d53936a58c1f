// The Figure 8 study from the shipped scenarios, against delay theory.
#include <gtest/gtest.h>

#include <cmath>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/studies/delay_compensation_study.h"

namespace rpsd::studies {
namespace {

DelayCompensationStudy shipped_delay_study(const std::string& name) {
  return std::get<DelayCompensationStudy>(
      scenarios::load_study(testing::source_dir() / "examples/scenarios" / name).study);
}

TEST(Figure8, UnderCompensationDestabilisesOverCompensationAddsDamping) {
  const auto study = shipped_delay_study("paper-fig8-delay-compensation.yaml");
  const auto cases = run_delay_compensation(study);
  ASSERT_EQ(cases.size(), study.compensated_delays_s.size());
  int under = 0, over = 0;
  for (const auto& c : cases) {
    if (c.residual_delay_s > 0.003) {
      // Beyond the critical residual delay (about 2 zeta / omega_n = 2.2 ms) the test is unstable.
      ++under;
      EXPECT_FALSE(c.stable) << c.compensated_delay_s;
      EXPECT_LT(c.identified_damping_ratio, 0.0) << c.compensated_delay_s;
    }
    if (c.residual_delay_s < 0.0) {
      // Over-compensation: stable, but more damped than the structure really is.
      ++over;
      EXPECT_TRUE(c.stable) << c.compensated_delay_s;
      EXPECT_GT(c.identified_damping_ratio, study.damping_ratio) << c.compensated_delay_s;
    }
    // The identified damping follows the exact DDE root of the residual delay; the gap grows with
    // the residual (the lead network's gain and the servo's amplitude loss shift the frequency,
    // and large growing responses open the valve further).
    if (std::abs(c.residual_delay_s) < 0.016) {
      EXPECT_NEAR(c.identified_damping_ratio, c.predicted_damping_ratio, 0.006) << c.compensated_delay_s;
    }
  }
  EXPECT_GE(under, 3);
  EXPECT_GE(over, 3);
}

TEST(Figure8, IdealDelayPlantMatchesTheRootOfTheCompensatedDelayLoop) {
  // With an exact delay actuator the only approximation left is the discrete loop itself: the
  // identified damping equals the root of m s^2 + c s + k G_c(s) e^{-s tau} = 0.
  const auto study = shipped_delay_study("paper-fig8-ideal-delay.yaml");
  for (const auto& c : run_delay_compensation(study)) {
    EXPECT_NEAR(c.identified_damping_ratio, c.predicted_damping_ratio_loop, 0.001) << c.compensated_delay_s;
  }
}

}  // namespace
}  // namespace rpsd::studies
