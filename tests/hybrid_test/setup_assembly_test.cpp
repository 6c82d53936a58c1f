// A whole test whose two DOFs (x, θ) a two-actuator setup drives, against the same test
// without a setup. Two actuators at heights +h and -h with h = 1 m have J = [[1, -1], [1, 1]],
// so two specimens of stiffness k under the actuators are, through Jᵀ diag(k, k) J, the
// DOF-diagonal specimen diag(2k, 2k): with perfect actuators the run reproduces, step for
// step, the run where each DOF is its own actuator on a specimen of 2k. The assembly holds the
// actuators at the strokes of the initial configuration, records their calibration, writes
// the DOF view only with a setup, and names the actuator that stopped a run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/hybrid_test/actuator_links.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/hybrid_test/setup_plan.h"
#include "two_actuator_test.h"

namespace rpsd::hybrid_test {
namespace {

TestRun run(const TestConfig& t, const std::filesystem::path& csv = {}) {
  TestAssembly assembly(t, {csv, false, true, {}});
  return assembly.finish(assembly.run({}, {}));
}

TEST(SetupAssembly, TwoActuatorsOnADofDiagonalSpecimenReproduceTheRunWithoutASetup) {
  const TestConfig plain = two_dof_test(2.0 * kK);
  const TestConfig driven = with_setup();
  const TestRun a = run(plain), b = run(driven);
  ASSERT_EQ(a.records.size(), 1024u);
  ASSERT_EQ(b.records.size(), a.records.size());
  double peak = 0.0, worst = 0.0, worst_force = 0.0;
  for (std::size_t n = 0; n < a.records.size(); ++n) {
    for (int d = 0; d < 2; ++d) {
      peak = std::max(peak, std::abs(a.records[n].displacement_m[d]));
      worst = std::max(worst, std::abs(a.records[n].displacement_m[d] - b.records[n].displacement_m[d]));
      worst = std::max(worst, std::abs(a.records[n].measured_m[d] - b.records[n].dof_measured_m[d]));
      worst_force =
          std::max(worst_force, std::abs(a.records[n].specimen_restoring_force_n[d] - b.records[n].dof_force_n[d]));
    }
    // The actuators' own view: s = x ∓ θ, and each load cell k s.
    const auto& r = b.records[n];
    EXPECT_NEAR(r.measured_m[0], r.dof_measured_m[0] - r.dof_measured_m[1], 1e-15);
    EXPECT_NEAR(r.measured_force_n[1], kK * (r.dof_measured_m[0] + r.dof_measured_m[1]), 1e-6);
  }
  EXPECT_GT(peak, 0.003);  // it moved
  EXPECT_LT(worst, 1e-12 * peak);
  EXPECT_LT(worst_force, 1e-12 * 2.0 * kK * peak);
}

TEST(SetupAssembly, TheActuatorsStartAtThePredictedStrokesAndTheCalibrationIsRecorded) {
  const TestConfig t = with_setup(setups::Geometry::kLargeDisplacement);
  TestAssembly assembly(t, {{}, false, true, {}});
  // Held at the strokes of (x, θ) = (4 mm, 3 mrad): the top attachment moves to
  // (x - sin θ, cos θ) from (0, 1), its fixed end at (-1.5, 1).
  const double x = 0.004, theta = 0.003;
  const double top = std::hypot(x - std::sin(theta) + 1.5, std::cos(theta) - 1.0) - 1.5;
  ASSERT_NE(assembly.actuators().simulated_plant(0), nullptr);
  EXPECT_NEAR(assembly.actuators().simulated_plant(0)->measure().displacement_m, top, 1e-15);
  const TestRun r = assembly.finish(assembly.run({}, {}));
  ASSERT_EQ(r.calibrations.size(), 1u);
  const SetupCalibration& c = r.calibrations[0];
  EXPECT_TRUE(c.measured);
  EXPECT_NEAR(c.predicted_stroke_m[0], top, 1e-15);
  EXPECT_EQ(c.offset_m[0], 0.0);  // a simulated actuator reads where it was put
  EXPECT_NEAR(c.reference_length_m[1], 1.5, 1e-15);
  EXPECT_EQ(c.actuators[1], "bottom");
}

TEST(SetupAssembly, AnOffsetBeyondTheLimitRefusesTheStartNamingTheActuator) {
  const TestConfig t = with_setup();
  Eigen::VectorXd hold(2);
  hold << 0.004, 0.003;
  SetupPlan plan = plan_setups(t, hold, 1.0 / 1024, false);
  EXPECT_NEAR(plan.hold_m[0], 0.004 - 0.003, 1e-15);  // s = x - θ on the top
  EXPECT_NEAR(plan.hold_m[1], 0.004 + 0.003, 1e-15);
  // Each force guard predicts with its own actuator's specimen: diag(J⁻ᵀ diag(2k, 2k) J⁻¹) = k.
  EXPECT_NEAR(plan.stiffness_estimate_n_per_m[0], kK, 1e-6);
  // Within max_calibration_offset_m (2 mm): recorded and used.
  std::vector<std::optional<double>> readings = {plan.hold_m[0] + 0.0015, plan.hold_m[1] - 0.001};
  const auto calibration = calibrate_setups(t, plan, readings);
  EXPECT_NEAR(calibration[0].offset_m[0], 0.0015, 1e-15);
  EXPECT_NEAR(plan.groups[0].calibration_offset_m[1], -0.001, 1e-15);
  // Beyond it: the run does not start.
  readings[1] = plan.hold_m[1] + 0.003;
  try {
    calibrate_setups(t, plan, readings);
    FAIL() << "a 3 mm offset started the run";
  } catch (const CalibrationOutOfRange& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("site 1, bottom (channel 1)"), std::string::npos) << what;
    EXPECT_NE(what.find("0.003 m from the stroke"), std::string::npos) << what;
    EXPECT_NE(what.find("max_calibration_offset_m 0.002"), std::string::npos) << what;
  }
}

TEST(SetupAssembly, TheCsvCarriesTheDofViewOnlyWithASetup) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "setup_assembly_csv";
  std::filesystem::create_directories(dir);
  const auto header = [](const std::filesystem::path& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    return line;
  };
  run(two_dof_test(2.0 * kK), dir / "plain.csv");
  run(with_setup(), dir / "driven.csv");
  EXPECT_EQ(header(dir / "plain.csv").find("dof_"), std::string::npos);
  const std::string driven = header(dir / "driven.csv");
  EXPECT_NE(driven.find("target_m_ch0,command_m_ch0,measured_m_ch0,measured_force_n_ch0"), std::string::npos);
  EXPECT_NE(driven.find(",dof_target_m_ch0,dof_measured_m_ch0,dof_force_n_ch0,dof_target_rad_ch1,"
                        "dof_measured_rad_ch1,dof_moment_n_m_ch1"),
            std::string::npos)
      << driven;
}

TEST(SetupAssembly, AnActuatorsLimitStopsTheRunNamingTheActuator) {
  TestConfig t = with_setup();
  t.setups[0].actuator_limits.resize(2);
  t.setups[0].actuator_limits[1].max_stroke_m = 0.0065;  // the bottom starts at 7 mm
  const TestRun r = run(t);
  EXPECT_EQ(r.outcome, coordinator::StepOutcome::kLimit);
  EXPECT_EQ(r.limit_stop.actuator, 1);
  EXPECT_EQ(std::string(r.limit_stop.name.data()), "site 1 actuator bottom");
  EXPECT_NE(coordinator::describe_limit_stop(r.limit_stop).find("site 1 actuator bottom (channel 1): its stroke"),
            std::string::npos)
      << coordinator::describe_limit_stop(r.limit_stop);
}

// From exchange 100 on, actuator 1 reads a stroke no configuration has; counts what is sent.
class ImpossibleReading final : public transport::Link {
 public:
  explicit ImpossibleReading(transport::Link& inner) : inner_(inner) {}
  transport::LinkStatus send(const transport::CommandSample& command) override {
    ++sent;
    return inner_.send(command);
  }
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override {
    const transport::LinkStatus status = inner_.receive(feedback);
    if (feedback.step >= 100) feedback.displacement_m[0] -= 5.0;  // shorter than the actuator itself
    return status;
  }
  int sent = 0;

 private:
  transport::Link& inner_;
};

TEST(SetupAssembly, AGeometryThatFailsStopsTheRunAndNothingMoreIsSent) {
  const TestConfig t = with_setup(setups::Geometry::kLargeDisplacement);
  ImpossibleReading* link = nullptr;
  AssemblyOptions options;
  options.keep_records = true;
  options.wrap_link = [&](transport::Link& inner) {
    auto wrapped = std::make_unique<ImpossibleReading>(inner);
    link = wrapped.get();
    return wrapped;
  };
  TestAssembly assembly(t, options);
  const TestRun r = assembly.finish(assembly.run({}, {}));
  EXPECT_EQ(r.outcome, coordinator::StepOutcome::kGeometry);
  EXPECT_EQ(r.steps, 100);  // exchanges 0..99 completed their steps
  ASSERT_NE(link, nullptr);
  EXPECT_EQ(link->sent, 101);  // the command of the failing exchange, and none after
  EXPECT_EQ(r.limit_stop.kind, coordinator::LimitStop::Kind::kGeometry);
  EXPECT_EQ(std::string(r.limit_stop.name.data()), "site 1 setup");
}

TEST(SetupAssembly, TheSummaryNamesTheActuatorThatStoppedTheRunAndDescribesTheSetup) {
  TestConfig t = with_setup();
  t.setups[0].actuator_limits.resize(2);
  t.setups[0].actuator_limits[1].max_stroke_m = 0.0065;
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "setup_assembly_summary";
  std::filesystem::remove_all(dir);
  TestDocument file;
  file.name = "two-dof";
  run_test_into(dir, file, t);
  std::ifstream in(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["stopped_by"]["kind"], "limit");
  EXPECT_EQ(summary["stopped_by"]["actuator"], "site 1 actuator bottom");
  EXPECT_EQ(summary["stopped_by"]["unit"], "m");
  EXPECT_NE(summary["outcome"].get<std::string>().find("site 1 actuator bottom (channel 1): its stroke"),
            std::string::npos)
      << summary["outcome"];
  const nlohmann::json& setup = summary["experimental_setups"][0];
  EXPECT_EQ(setup["kind"], "planar");
  EXPECT_EQ(setup["geometry"], "linear");
  EXPECT_EQ(setup["actuators"][1]["name"], "bottom");
  EXPECT_EQ(setup["actuators"][1]["channel"], 1);
  EXPECT_DOUBLE_EQ(setup["actuators"][1]["reference_length_m"].get<double>(), 1.5);
  EXPECT_EQ(setup["dofs"][1]["motion"], "rotation");
  EXPECT_EQ(setup["calibration"]["offset_m"], nlohmann::json::array({0.0, 0.0}));
  EXPECT_NEAR(setup["calibration"]["predicted_stroke_m"][1].get<double>(), 0.007, 1e-15);
}

}  // namespace
}  // namespace rpsd::hybrid_test
