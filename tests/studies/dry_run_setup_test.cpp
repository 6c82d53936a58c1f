// The dry run of a test whose DOFs a two-actuator setup drives: the channels' predictions are
// the actuators' (their strokes against each actuator's own limits), and the DOFs' are the
// DOFs' (x in m, θ in rad, against the DOFs' limits), from the same simulated run. The
// actuators sit at heights +1 m and -1 m: strokes s = x ∓ θ.
#include <gtest/gtest.h>

#include <sstream>

#include "../hybrid_test/two_actuator_test.h"
#include "rpsd/studies/dry_run.h"
#include "rpsd/studies/dry_run_report.h"

namespace rpsd::studies {
namespace {

using namespace hybrid_test;

TEST(DryRunSetup, PredictsEachActuatorAgainstItsLimitsAndEachDofAgainstItsOwn) {
  TestConfig t = with_setup();
  t.setups[0].actuator_limits.resize(2);
  t.setups[0].actuator_limits[1].max_stroke_m = 0.02;
  t.experimental[1].limits.max_stroke_m = 0.0035;  // rad: the rotation starts at 3 mrad
  const DryRunReport r = dry_run(t);
  ASSERT_EQ(r.outcome, coordinator::StepOutcome::kOk);
  ASSERT_EQ(r.dofs.size(), 2u);
  // The bottom actuator starts at x + θ = 7 mm; its limit is its own, not the DOF's.
  EXPECT_NEAR(r.channels[1].peak_displacement_m, 0.007, 1e-4);
  EXPECT_EQ(r.channels[1].limits.max_stroke_m, 0.02);
  EXPECT_TRUE(r.channels[1].within_limits);
  EXPECT_EQ(r.dofs[1].motion, "rotation");
  EXPECT_NEAR(r.dofs[1].peak_displacement_m, 0.003, 1e-4);
  EXPECT_NEAR(r.dofs[1].peak_force_n, 2.0 * kK * 0.003, 0.05 * 2.0 * kK * 0.003);  // N·m
  EXPECT_TRUE(r.dofs[1].within_limits);
  EXPECT_TRUE(r.within_limits);
  std::ostringstream text;
  const nlohmann::json json = report_dry_run(r, "two-dof", text);
  EXPECT_NE(text.str().find("DOF on channel 1 (site 1, rotation): displacement 3 / 3.5 mrad, force 2.4 kN·m"),
            std::string::npos)
      << text.str();
  EXPECT_EQ(json["dofs"][1]["unit"], "rad");
  EXPECT_EQ(json["channels"][1]["limits"]["max_stroke_m"], 0.02);
}

TEST(DryRunSetup, ADofBeyondItsLimitIsNotReadyAndNamed) {
  TestConfig t = with_setup();
  t.experimental[1].limits.max_stroke_m = 0.0025;  // rad
  const DryRunReport r = dry_run(t);
  EXPECT_EQ(r.outcome, coordinator::StepOutcome::kLimit);
  EXPECT_EQ(r.limit_stop.dof, 1);
  EXPECT_GT(r.dofs[1].peak_target_m, 0.0025);
  EXPECT_FALSE(r.dofs[1].within_limits);
  EXPECT_FALSE(r.within_limits);
  std::ostringstream text;
  report_dry_run(r, "two-dof", text);
  EXPECT_NE(text.str().find("site 1 DOF rotation (channel 1): its target"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("/ 2.5 mrad  EXCEEDED"), std::string::npos) << text.str();
}

TEST(DryRunSetup, WithoutASetupTheReportHasNoDofs) {
  const DryRunReport r = dry_run(two_dof_test(2.0 * kK));
  EXPECT_TRUE(r.dofs.empty());
  std::ostringstream text;
  EXPECT_FALSE(report_dry_run(r, "two-dof", text).contains("dofs"));
}

}  // namespace
}  // namespace rpsd::studies
