// rpsd_test scenarios: typed values, located errors, --set overrides.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "../servo/paper_rig.h"
#include "example_files.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::scenarios {
namespace {

std::string error_of(const std::vector<Override>& overrides) {
  try {
    load_study(example(), overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(TestScenarioFile, ReadsTheTypedScenario) {
  const auto file = load_study(example());
  const auto& t = std::get<hybrid_test::TestConfig>(file.study);
  EXPECT_EQ(structure_dofs(t), 1);
  ASSERT_EQ(t.experimental.size(), 1u);
  EXPECT_DOUBLE_EQ(t.experimental[0].dof.specimen_stiffness_estimate_n_per_m, 700.8e3);
  EXPECT_EQ(t.experimental[0].restoring_force, coordinator::RestoringForceSource::kStiffnessTimesMeasuredDisplacement);
  EXPECT_DOUBLE_EQ(std::get<servo::PureDelayParameters>(t.plant).delay_s, 0.005);
  const auto& comp = std::get<compensation::PolynomialExtrapolationParameters>(t.compensation);
  EXPECT_EQ(comp.order, 3);
  EXPECT_DOUBLE_EQ(t.control_rate_hz, 1024.0);
  EXPECT_DOUBLE_EQ(t.initial_displacement_m[0], 0.01);
  EXPECT_DOUBLE_EQ(t.duration_s, 5.0);
  // c = 2 zeta sqrt(k m)
  const auto& linear = std::get<substructure::LinearMdofParameters>(t.structure);
  const auto& c = std::get<substructure::DampingMatrix>(linear.damping).c;
  EXPECT_NEAR(c.coeff(0, 0), 2.0 * 0.011 * std::sqrt(700.8e3 * 7080.0), 1e-9);
}

TEST(TestScenarioFile, OverridesReplaceValuesAndAreSavedInTheEffectiveScenario) {
  const auto file =
      load_study(example(), {parse_override("servo.delay_s=0.02"), parse_override("clock.control_rate_hz=2048")});
  const auto& t = std::get<hybrid_test::TestConfig>(file.study);
  EXPECT_DOUBLE_EQ(std::get<servo::PureDelayParameters>(t.plant).delay_s, 0.02);
  EXPECT_DOUBLE_EQ(t.control_rate_hz, 2048.0);
  EXPECT_NE(file.effective_yaml.find("delay_s: 0.02"), std::string::npos) << file.effective_yaml;
}

// A real-time run keeps the CPUs out of slow idle states unless the scenario says not to.
TEST(TestScenarioFile, KeepingTheCpusAwakeIsOnUnlessTurnedOff) {
  EXPECT_TRUE(std::get<hybrid_test::TestConfig>(load_study(example()).study).clock.realtime.keep_cpus_awake);
  EXPECT_FALSE(
      std::get<hybrid_test::TestConfig>(load_study(example(), {parse_override("clock.keep_cpus_awake=false")}).study)
          .clock.realtime.keep_cpus_awake);
  EXPECT_NE(error_of({parse_override("clock.keep_cpus_awake=sometimes")}).find("clock.keep_cpus_awake"),
            std::string::npos);
}

TEST(TestScenarioFile, ErrorsNameTheKeyPath) {
  EXPECT_NE(error_of({parse_override("experimental.0.dof=3")})
                .find("experimental[0].dof: expected a whole number from 0 to 0"),
            std::string::npos);
  EXPECT_NE(error_of({parse_override("servo.kind=hydraulic")})
                .find("servo.kind: expected servo_model, ideal_delay, transfer_function or feedback_controlled, got "
                      "\"hydraulic\""),
            std::string::npos);
  EXPECT_NE(
      error_of({parse_override("clock.mode=sometimes")}).find("clock.mode: expected as_fast_as_possible or real_time"),
      std::string::npos);
  EXPECT_NE(error_of({parse_override("clock.fifo_priority=120")}).find("clock.fifo_priority"), std::string::npos);
  EXPECT_NE(error_of({parse_override("clock.loop_cpu=1024")}).find("clock.loop_cpu"), std::string::npos);
  EXPECT_NE(error_of({parse_override("clock.loop_cpu=-2")}).find("clock.loop_cpu"), std::string::npos);
  EXPECT_NE(error_of({parse_override("experimental.0.site=0")}).find("experimental[0].site"), std::string::npos);
  EXPECT_NE(
      error_of({parse_override("integrator.scheme=euler")})
          .find("integrator.scheme: unknown integrator \"euler\"; expected central_difference, newmark, hht_alpha, "
                "generalized_alpha, alpha_os, chang, chen_ricles or kolay_ricles_alpha"),
      std::string::npos);
  EXPECT_NE(error_of({parse_override("experimental.0.restoring_force=guess")}).find("experimental[0].restoring_force"),
            std::string::npos);
  EXPECT_NE(error_of({parse_override("structure.colour=red")}).find("structure.colour: unknown key"),
            std::string::npos);
  // A key --set creates is checked like any other, and the error names the override.
  EXPECT_NE(error_of({parse_override("nothing.here=1")}).find("--set (nothing.here=1): nothing: unknown key"),
            std::string::npos);
  // An error in a value the command line gave names the override, not a line of the file.
  Override second = parse_override("compensation.order=7");
  second.origin = "--set #2";
  EXPECT_EQ(error_of({parse_override("clock.mode=as_fast_as_possible"), second}),
            "--set #2 (compensation.order=7): compensation.order: expected a whole number from 0 to 3, got \"7\"");
  // An error in the file keeps file:line:column (a phase lead needs its ratio_a).
  EXPECT_TRUE(std::regex_search(
      error_of({parse_override("compensation.kind=phase_lead")}),
      std::regex(R"(sdof-free-vibration\.yaml:23:3: compensation\.ratio_a: required key is missing)")))
      << error_of({parse_override("compensation.kind=phase_lead")});
}

// The lock-step busy wait: read as given, refused with a real-time clock (a spinning loop
// could starve its own receive thread), negative or beyond 10 ms.
TEST(TestScenarioFile, BusyWaitIsForLockStepOnly) {
  const auto file = load_study(example(), {parse_override("transport={kind: dds, busy_wait_s: 0.0002}")});
  EXPECT_DOUBLE_EQ(std::get<hybrid_test::TestConfig>(file.study).transport.busy_wait_s, 0.0002);
  EXPECT_DOUBLE_EQ(std::get<hybrid_test::TestConfig>(load_study(example()).study).transport.busy_wait_s, 0.0);
  EXPECT_NE(
      error_of({parse_override("transport={kind: dds, busy_wait_s: 0.0002}"), parse_override("clock.mode=real_time")})
          .find("transport.busy_wait_s: lock-step only"),
      std::string::npos);
  EXPECT_NE(error_of({parse_override("transport={kind: dds, busy_wait_s: -1}")}).find("transport.busy_wait_s"),
            std::string::npos);
  EXPECT_NE(error_of({parse_override("transport={kind: dds, busy_wait_s: 0.5}")})
                .find("transport.busy_wait_s: expected a number 0 to 0.01"),
            std::string::npos);
}

// clock.loop_timing: rpsd's end of step unless the benchmark's is named; the benchmark's holds
// one command a step, so an integrator that exchanges more often is refused by name, and a
// site server, whose loop OpenSees times, takes rpsd's only.
TEST(TestScenarioFile, LoopTimingIsEndOfStepUnlessTheBenchmarksIsNamed) {
  const auto timing = [](const std::vector<Override>& overrides) {
    return std::get<hybrid_test::TestConfig>(load_study(example(), overrides).study).clock.loop_timing;
  };
  EXPECT_EQ(timing({}), coordinator::LoopTiming::kEndOfStep);
  EXPECT_EQ(timing({parse_override("clock.loop_timing=target_now_force_delayed")}),
            coordinator::LoopTiming::kTargetNowForceDelayed);
  EXPECT_EQ(timing({parse_override("clock.loop_timing=end_of_step")}), coordinator::LoopTiming::kEndOfStep);
  const std::string unknown = error_of({parse_override("clock.loop_timing=benchmark")});
  EXPECT_NE(unknown.find("clock.loop_timing: expected end_of_step or target_now_force_delayed"), std::string::npos)
      << unknown;
  const std::string iterative = error_of(
      {parse_override("clock.loop_timing=target_now_force_delayed"), parse_override("integrator.scheme=newmark")});
  EXPECT_NE(iterative.find("clock.loop_timing: target_now_force_delayed holds one command and one force per step; "
                           "integrator newmark exchanges 2 times a step"),
            std::string::npos)
      << iterative;
  const auto site = testing::source_dir() / "tests/scenarios/data/reference/site-server.yaml";
  EXPECT_NO_THROW(load_site_server(site, {}));
  try {
    load_site_server(site, {parse_override("clock.loop_timing=target_now_force_delayed")});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("clock.loop_timing must be end_of_step"), std::string::npos) << e.what();
  }
}

// output.histories: every step by default; decimated keeps every k-th step, k = control rate /
// history_rate_hz, a whole number; the rate is refused at its key when it is not one.
TEST(TestScenarioFile, HistoriesKeepEveryStepUnlessToldAndARateMustDivideTheControlRate) {
  using Kept = hybrid_test::HistoriesConfig::Kept;
  // The example has no output section: each override list gives its one required key first.
  const auto with_output = [](std::vector<Override> overrides) {
    overrides.insert(overrides.begin(), parse_override("output.record_dofs=[0]"));
    return overrides;
  };
  const auto histories = [&](const std::vector<Override>& overrides) {
    return std::get<hybrid_test::TestConfig>(load_study(example(), with_output(overrides)).study).histories;
  };
  EXPECT_EQ(histories({}).kept, Kept::kAll);
  EXPECT_EQ(histories({}).every_steps, 1);
  const auto decimated =
      histories({parse_override("output.histories=decimated"), parse_override("output.history_rate_hz=128")});
  EXPECT_EQ(decimated.kept, Kept::kDecimated);
  EXPECT_EQ(decimated.every_steps, 8);  // 1024 Hz / 128 Hz
  EXPECT_DOUBLE_EQ(decimated.rate_hz, 128.0);
  EXPECT_EQ(histories({parse_override("output.histories=criteria_only")}).kept, Kept::kCriteriaOnly);
  // Beside all, a rate is unused: --histories all overrides a file that decimates.
  const auto all = histories({parse_override("output.histories=all"), parse_override("output.history_rate_hz=100")});
  EXPECT_EQ(all.kept, Kept::kAll);
  EXPECT_EQ(all.every_steps, 1);
  EXPECT_NE(error_of(with_output(
                         {parse_override("output.histories=decimated"), parse_override("output.history_rate_hz=100")}))
                .find("output.history_rate_hz: does not divide the control rate (1024 Hz)"),
            std::string::npos);
  EXPECT_NE(error_of(with_output(
                         {parse_override("output.histories=decimated"), parse_override("output.history_rate_hz=2048")}))
                .find("output.history_rate_hz: above the control rate"),
            std::string::npos);
  EXPECT_NE(
      error_of(with_output({parse_override("output.histories=decimated")})).find("output.histories: decimated needs"),
      std::string::npos);
  EXPECT_NE(
      error_of(with_output({parse_override("output.history_rate_hz=128")})).find("output.history_rate_hz: only with"),
      std::string::npos);
}

TEST(TestScenarioFile, OverrideNeedsAnEqualsSign) { EXPECT_THROW(parse_override("servo.delay_s"), ConfigError); }

}  // namespace
}  // namespace rpsd::scenarios

namespace rpsd::scenarios {
namespace {

TEST(SweepFile, EveryCaseIsReadWithItsValuesFirstAxisFastest) {
  const auto file = load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof-compensation-sweep.yaml");
  ASSERT_EQ(file.sweep.size(), 2u);
  EXPECT_EQ(file.sweep[0].key_path, "compensation.delay_s");
  ASSERT_EQ(file.sweep[0].values.size(), 4u);
  EXPECT_DOUBLE_EQ(file.sweep[0].values[0], 0.08);
  EXPECT_DOUBLE_EQ(file.sweep[0].values[3], 0.11);
  ASSERT_EQ(file.sweep_cases.size(), 8u);
  for (std::size_t c = 0; c < 8; ++c) {
    const auto& lead = std::get<compensation::DiscretePhaseLeadParameters>(file.sweep_cases[c].compensation).network;
    // The design rule (a - 1) T = delay holds with the case's own values.
    EXPECT_NEAR((lead.ratio_a - 1.0) * lead.time_constant_s, file.sweep_values[c][0], 1e-12);
    EXPECT_DOUBLE_EQ(lead.ratio_a, file.sweep_values[c][1]);
    EXPECT_DOUBLE_EQ(file.sweep_values[c][0], file.sweep[0].values[c % 4]);
  }
}

// The sweep's effective document names its files by absolute path, keeps its sweep, and read
// from another folder gives the same cases.
TEST(SweepFile, ItsEffectiveDocumentReadsTheSameFromAnotherFolder) {
  const auto sweep = load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof-compensation-sweep.yaml");
  const std::string servo = (testing::source_dir() / "examples/servo/paper-mts-244.yaml").lexically_normal().string();
  EXPECT_NE(sweep.effective_yaml.find("parameters: " + servo), std::string::npos) << sweep.effective_yaml;
  const auto again =
      parse_study(sweep.effective_yaml, std::filesystem::temp_directory_path() / "elsewhere" / "effective.yaml");
  ASSERT_EQ(again.sweep_cases.size(), sweep.sweep_cases.size());
  EXPECT_EQ(servo::envelope_of(again.sweep_cases.back().plant).force_n,
            servo::envelope_of(sweep.sweep_cases.back().plant).force_n);
  EXPECT_EQ(again.sweep_cases.back().ground_motion->acceleration_m_per_s2,
            sweep.sweep_cases.back().ground_motion->acceleration_m_per_s2);
}

TEST(SweepFile, ABadCaseIsNamedBeforeAnythingRuns) {
  try {
    load_study(testing::source_dir() / "examples/scenarios/elcentro-sdof-compensation-sweep.yaml",
               {parse_override("sweep.1.values=[10, 0.5]")});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("(sweep case compensation.delay_s = 0.08, compensation.ratio_a = 0.5)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rpsd::scenarios

namespace rpsd::scenarios {
namespace {

// Found by the scenario fuzz target: a second `sweep:` key made every case sweep again.
TEST(ScenarioText, RepeatedKeysAreRejectedWithTheirLine) {
  const std::string text =
      "study: rpsd_test\nsweep:\n  - {key: servo.delay_s, values: [0.01]}\nsweep:\n  - {key: servo.delay_s, values: "
      "[0.02]}\n";
  try {
    parse_study(text, testing::source_dir() / "examples/scenarios/inline.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("inline.yaml:4:1: sweep: given more than once"), std::string::npos)
        << e.what();
  }
}

TEST(ScenarioText, DeepNestingIsASyntaxErrorNotACrash) {
  const std::string text = "study: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  EXPECT_THROW(parse_study(text, "deep.yaml"), ConfigError);
}

TEST(TestScenarioFile, OperatorCommandsAreOffByDefaultAndAReturnToStartNeedsItsVelocity) {
  const auto plain = load_study(example());
  const auto& off = std::get<hybrid_test::TestConfig>(plain.study).operator_commands;
  EXPECT_FALSE(off.enabled);
  EXPECT_FALSE(off.return_to_start);
  const auto file = load_study(
      example(),
      {parse_override("operator_commands={enabled: true, return_to_start: true, return_velocity_m_per_s: 0.02}")});
  const auto& on = std::get<hybrid_test::TestConfig>(file.study).operator_commands;
  EXPECT_TRUE(on.enabled);
  EXPECT_TRUE(on.return_to_start);
  EXPECT_DOUBLE_EQ(on.return_velocity_m_per_s, 0.02);
  // Refused without a velocity: a return at an unstated rate is no safe state.
  EXPECT_NE(error_of({parse_override("operator_commands={return_to_start: true}")})
                .find("operator_commands.return_to_start: needs return_velocity_m_per_s > 0"),
            std::string::npos)
      << error_of({parse_override("operator_commands={return_to_start: true}")});
}

}  // namespace
}  // namespace rpsd::scenarios
