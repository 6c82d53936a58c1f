// The coordinator loop allocates nothing per step: integrator, substructure, compensator,
// in-process link, plant and recorder hand-off, for each plant kind and several compensators.
#include <gtest/gtest.h>

#include "allocation_counter.h"
#include "rpsd/coordinator/sdof_rpsd.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/transfer_function_plant.h"
#include "../servo/paper_rig.h"

namespace rpsd::coordinator {
namespace {

long allocations_over_steps(const SdofRpsdSetup& setup, servo::Plant& plant, int steps) {
  SdofRpsdTest test(setup, plant);
  rpsd::testing::begin_counting_allocations();
  for (int i = 0; i < steps; ++i) {
    if (test.step() != StepOutcome::kOk) break;
  }
  const long allocations = rpsd::testing::end_counting_allocations().total();
  EXPECT_EQ(test.finish().size(), static_cast<std::size_t>(steps));
  return allocations;
}

TEST(LoopAllocation, CounterSeesAllocations) {
  rpsd::testing::begin_counting_allocations();
  auto* p = new int(1);
  rpsd::testing::keep(p);
  delete p;
  EXPECT_EQ(rpsd::testing::end_counting_allocations().operator_new, 1);
}

TEST(LoopAllocation, NoAllocationPerStep) {
  SdofRpsdSetup setup;
  setup.initial_displacement_m = 0.005;
  const compensation::CompensatorConfig compensators[] = {
      compensation::PassThroughParameters{},
      compensation::PolynomialExtrapolationParameters{3, 0.02},
      compensation::DiscretePhaseLeadParameters::for_delay(0.08, 5.0),
      compensation::AdaptiveTimeSeriesParameters{},
  };
  const integrators::IntegratorConfig integrators[] = {integrators::CentralDifferenceParams{},
                                                       integrators::KolayRiclesAlphaParams{},
                                                       integrators::HhtAlphaParams{}};
  for (const auto& compensator : compensators) {
    for (const auto& integrator : integrators) {
      setup.compensator = compensator;
      setup.integrator = integrator;
      servo::PureDelayPlant delay({0.02, setup.stiffness_n_per_m, 8192.0});
      EXPECT_EQ(allocations_over_steps(setup, delay, 4000), 0) << compensation::compensator_name(compensator);
      servo::ServoHydraulicPlant paper(rpsd::testing::paper_rig());
      EXPECT_EQ(allocations_over_steps(setup, paper, 2000), 0) << compensation::compensator_name(compensator);
      // The RTHS benchmark's fifth-order plant.
      servo::TransferFunctionPlant benchmark(
          {{servo::Polynomial{2.18385e13}, servo::Polynomial{2.16756e13, 5.43547e11, 2.32849e9, 8.42178e6, 1.25906e4, 29.13}},
           setup.stiffness_n_per_m, 8192.0});
      EXPECT_EQ(allocations_over_steps(setup, benchmark, 2000), 0) << compensation::compensator_name(compensator);
    }
  }
}

}  // namespace
}  // namespace rpsd::coordinator
