// The coordinator loop allocates nothing per step: integrator, substructure, compensator,
// in-process link, plant and recorder hand-off, for each plant kind and several compensators.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "../hybrid_test/two_actuator_test.h"
#include "../servo/paper_rig.h"
#include "allocation_counter.h"
#include "claimed_dds_domain.h"
#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/hdf5_output/hdf5_results.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/specimen_sdof.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/telemetry/telemetry_publisher.h"
#include "rpsd/telemetry/telemetry_subscriber.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

// The whole test as rpsd runs it: loop, in-process servo node (controller, limits, watchdog),
// simulated actuator, recorder hand-off.
long allocations_over_steps(SpecimenSdof sdof, const servo::PlantConfig& plant, int steps,
                            LoopTiming timing = LoopTiming::kEndOfStep) {
  sdof.plant = plant;
  sdof.duration_s = 2.0 * steps / sdof.control_rate_hz;
  TestConfig config = specimen_sdof_test(sdof);
  config.clock.loop_timing = timing;
  TestAssembly test(config, {{}, false, true, {}});
  int taken = 0;
  rpsd::testing::begin_counting_allocations();
  for (; taken < steps; ++taken) {
    if (test.step() != StepOutcome::kOk) break;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  // A combination that runs away (HHT's two commands a step with adaptive time series grow past
  // the rig's velocity) stops early: its stop must not allocate either.
  EXPECT_GE(taken, 500) << "the test stopped: " << limit_stop_name(test.limit_stop().kind);
  EXPECT_EQ(test.finish(StepOutcome::kOk).records.size(), static_cast<std::size_t>(taken));
  return allocations;
}

// With the telemetry on, a subscriber reading it: the publisher runs on the recorder's writer
// thread (it allocates there, for its events' texts), the loop's thread allocates nothing.
TEST(LoopAllocation, NoAllocationPerStepWithTelemetryPublishedAndRead) {
  SpecimenSdof sdof;
  sdof.duration_s = 8.0;
  const TestConfig config = specimen_sdof_test(sdof);
  const auto domain = ::rpsd::testing::claimed_dds_domain();
  const std::string xml = std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/loopback.xml";
  telemetry::TelemetrySubscriber subscriber({domain, xml, 21});
  telemetry::TelemetryPublisher publisher({domain, xml, 21, "allocation", 1024.0});  // every step
  std::atomic<bool> done{false};
  std::size_t batches_read = 0;
  std::thread reader([&] {
    std::vector<telemetry::TelemetryBatch> batches;
    std::vector<telemetry::TelemetryEvent> events;
    while (!done.load()) {
      subscriber.wait(std::chrono::milliseconds(20));
      subscriber.take(batches, events);
    }
    batches_read = batches.size();
  });
  TestAssembly test(config, {{}, false, true, {}, nullptr, {&publisher}});
  telemetry::TelemetryRunInfo info;
  info.run_id = test.run_id();
  info.steps_planned = test.steps_planned();
  info.control_rate_hz = config.control_rate_hz;
  info.channels = 1;
  info.live = &test.live_counters();
  publisher.start(info);
  int taken = 0;
  rpsd::testing::begin_counting_allocations();
  for (; taken < 6000; ++taken) {
    if (test.step() != StepOutcome::kOk) break;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(taken, 6000);
  EXPECT_EQ(test.finish(StepOutcome::kOk).records.size(), 6000u);
  publisher.end({});
  done.store(true);
  reader.join();
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(publisher.batches_sent(), 6000u / telemetry::kSamplesPerBatch - 1);  // it did publish
  EXPECT_GT(batches_read, 0u);
}

// With results.h5 written as the test runs: the HDF5 writer buffers, compresses and writes on
// the recorder's writer thread (allocating there), the loop's thread allocates nothing.
TEST(LoopAllocation, NoAllocationPerStepWithResultsH5Written) {
  SpecimenSdof sdof;
  sdof.duration_s = 8.0;
  const TestConfig config = specimen_sdof_test(sdof);
  const auto path =
      std::filesystem::temp_directory_path() / ("rpsd-loop-allocation-" + std::to_string(::getpid()) + ".h5");
  hdf5_output::Hdf5RunLayout layout;
  layout.name = "test";
  layout.control_rate_hz = config.control_rate_hz;
  layout.channels = 1;
  for (auto d : config.record_dofs) layout.dof_numbers.push_back(static_cast<std::int64_t>(d));
  hdf5_output::Hdf5Results results(path, {"allocation", "", {}}, {layout});
  TestAssembly test(config, {{}, false, true, {}, nullptr, {&results.observer(0)}});
  int taken = 0;
  rpsd::testing::begin_counting_allocations();
  for (; taken < 6000; ++taken) {
    if (test.step() != StepOutcome::kOk) break;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(taken, 6000);
  EXPECT_EQ(test.finish(StepOutcome::kOk).records.size(), 6000u);
  EXPECT_EQ(results.close(), "");
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(std::filesystem::file_size(path), 6000u * 8u / 10u);  // it did write
  std::filesystem::remove(path);
}

TEST(LoopAllocation, CounterSeesAllocations) {
  rpsd::testing::begin_counting_allocations();
  auto* p = new int(1);
  rpsd::testing::keep(p);
  delete p;
  EXPECT_EQ(rpsd::testing::end_counting_allocations().operator_new, 1);
}

TEST(LoopAllocation, NoAllocationPerStep) {
  SpecimenSdof setup;
  // Small enough that the combinations that grow (the uncompensated ones) stay within the rig's
  // envelope for most of the steps counted.
  setup.initial_displacement_m = 0.0002;
  const compensation::CompensatorConfig compensators[] = {
      compensation::PassThroughParameters{},
      compensation::PolynomialExtrapolationParameters{3, 0.02},
      compensation::DiscretePhaseLeadParameters::for_delay(0.08, 5.0),
      compensation::AdaptiveTimeSeriesParameters{},
      // The benchmark's phase lead G_T = 50.8 (s + 168.6) / (s + 8570), Tustin.
      compensation::LtiFilterParameters{{{50.8, 8564.88}, {1.0, 8570.0}}, 0.0},
  };
  const integrators::IntegratorConfig integrators[] = {integrators::CentralDifferenceParameters{},
                                                       integrators::KolayRiclesAlphaParameters{},
                                                       integrators::HhtAlphaParameters{}};
  for (const auto& compensator : compensators) {
    for (const auto& integrator : integrators) {
      setup.compensation = compensator;
      setup.integrator = integrator;
      const servo::PureDelayParameters delay{0.02, setup.stiffness_n_per_m, 8192.0, {}};
      EXPECT_EQ(allocations_over_steps(setup, delay, 4000), 0) << compensation::compensator_name(compensator);
      EXPECT_EQ(allocations_over_steps(setup, rpsd::testing::paper_rig(), 2000), 0)
          << compensation::compensator_name(compensator);
      // The RTHS benchmark's fifth-order plant.
      const servo::TransferFunctionPlantParameters benchmark{
          {servo::Polynomial{2.18385e13},
           servo::Polynomial{2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13}},
          setup.stiffness_n_per_m,
          8192.0,
          {}};
      EXPECT_EQ(allocations_over_steps(setup, benchmark, 2000), 0) << compensation::compensator_name(compensator);
      // The same under the benchmark's sample PI controller, with its converters and noise, and
      // a specimen with damping and mass.
      servo::FeedbackControlledPlantParameters controlled;
      controlled.plant = benchmark;
      controlled.plant.specimen_damping_n_s_per_m = 114.22;
      controlled.plant.specimen_mass_kg = 29.13;
      controlled.controller = servo::PidGains{2.0, 95.0, 0.0, 0.0};
      controlled.converters.command = {7.89e-3, 0.0, 3.8, 18, 0.0, 1};
      controlled.converters.displacement = {7.89e-3, 0.002, 10.0, 18, 0.0, 2};
      controlled.converters.force = {1096.0, 0.002, 10.0, 18, 0.0, 3};
      EXPECT_EQ(allocations_over_steps(setup, controlled, 2000), 0) << compensation::compensator_name(compensator);
    }
  }
}

// The benchmark's loop timing holds the step's target and force in buffers sized at start.
TEST(LoopAllocation, NoAllocationPerStepUnderTheBenchmarksLoopTiming) {
  SpecimenSdof setup;
  setup.initial_displacement_m = 0.0002;
  setup.compensation = compensation::LtiFilterParameters{{{50.8, 8564.88}, {1.0, 8570.0}}, 0.0};
  for (const integrators::IntegratorConfig& integrator :
       {integrators::IntegratorConfig{integrators::CentralDifferenceParameters{}},
        integrators::IntegratorConfig{integrators::KolayRiclesAlphaParameters{}}}) {
    setup.integrator = integrator;
    const servo::PureDelayParameters delay{0.002, setup.stiffness_n_per_m, 8192.0, {}};
    EXPECT_EQ(allocations_over_steps(setup, delay, 4000, LoopTiming::kTargetNowForceDelayed), 0);
    EXPECT_EQ(allocations_over_steps(setup, rpsd::testing::paper_rig(), 2000, LoopTiming::kTargetNowForceDelayed), 0);
  }
}

// Through a large-displacement setup (strokes from the displaced attachment points, Newton
// from the measured strokes every exchange, Jᵀ f at the measured configuration), its
// compensators on the actuators or on the DOFs, with per-actuator and DOF limits in force.
TEST(LoopAllocation, NoAllocationPerStepThroughALargeDisplacementSetup) {
  for (const auto compensated :
       {ExperimentalSetupSite::Compensated::kActuators, ExperimentalSetupSite::Compensated::kDofs}) {
    TestConfig config = with_setup(setups::Geometry::kLargeDisplacement);
    config.duration_s = 3.0;
    config.compensation = compensation::PolynomialExtrapolationParameters{3, 0.002};
    config.setups[0].compensated = compensated;
    config.setups[0].actuator_limits.resize(2);
    config.experimental[1].limits.max_force_n = 1e9;
    TestAssembly test(config, {{}, false, true, {}});
    int taken = 0;
    rpsd::testing::begin_counting_allocations();
    for (; taken < 2000; ++taken) {
      if (test.step() != StepOutcome::kOk) break;
    }
    const long allocations = rpsd::testing::end_counting_allocations().total();
    EXPECT_EQ(taken, 2000) << describe_limit_stop(test.limit_stop());
    EXPECT_EQ(allocations, 0);
    EXPECT_GT(std::abs(test.last_record().dof_measured_m[1]), 0.0);  // Newton ran on a moving specimen
    test.finish(StepOutcome::kOk);
  }
}

// With a held force (examples/scenarios/column-axial-load.yaml): its ramp, its force-mode
// command, its limits and its record, through the in-process node's force loop.
TEST(LoopAllocation, NoAllocationPerStepWithAHeldForce) {
  const TestConfig config =
      std::get<TestConfig>(scenarios::load_study(testing::source_dir() / "examples/scenarios/column-axial-load.yaml",
                                                 {scenarios::parse_override("ground_motion.trim={end_s: 4}")})
                               .study);
  ASSERT_EQ(config.held_forces.size(), 1u);
  TestAssembly test(config, {{}, false, true, {}});
  int taken = 0;
  rpsd::testing::begin_counting_allocations();
  for (; taken < 3000; ++taken) {
    if (test.step() != StepOutcome::kOk) break;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(taken, 3000) << describe_limit_stop(test.limit_stop());
  EXPECT_EQ(allocations, 0);
  EXPECT_LT(test.last_record().held_force_command_n[0], -1.0e3);  // the ramp is under way
  test.finish(StepOutcome::kOk);
}

// An operator's flags attached (operator_commands/): the loop reads them between steps and
// allocates nothing more, with none set and with a stop set (the run ends on it).
TEST(LoopAllocation, NoAllocationPerStepWithAnOperatorsFlagsAttached) {
  SpecimenSdof sdof;
  sdof.initial_displacement_m = 0.0002;
  sdof.plant = rpsd::testing::paper_rig();
  sdof.duration_s = 4000.0 / sdof.control_rate_hz;
  const TestConfig config = specimen_sdof_test(sdof);
  operator_commands::OperatorControl control;
  AssemblyOptions options;
  options.keep_records = true;
  options.operator_control = &control;
  TestAssembly test(config, options);
  int taken = 0;
  rpsd::testing::begin_counting_allocations();
  for (; taken < 2000; ++taken) {
    if (test.step() != StepOutcome::kOk) break;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(taken, 2000);
  EXPECT_EQ(allocations, 0);
  control.request_stop("operator");  // the name is copied here, off the loop
  rpsd::testing::begin_counting_allocations();
  const StepOutcome stopped = test.step();
  const long at_stop = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(stopped, StepOutcome::kOperatorStop);
  EXPECT_EQ(test.finish(stopped).steps, 2001);
  RecordProperty("allocations_at_the_stop", std::to_string(at_stop));
}

}  // namespace
}  // namespace rpsd::coordinator
