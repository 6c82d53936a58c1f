// Every plant kind registered in PlantKinds advances and measures without allocating: a
// node's control loop steps them every period. A typed suite over the list, so a new kind is
// covered without a new test line as soon as its default parameters make a working plant
// (example_of below gives parameters where the defaults do not).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include "allocation_counter.h"
#include "kind_types.h"
#include "paper_rig.h"
#include "rpsd/servo/coupled_specimen_actuator.h"
#include "rpsd/servo/plant_factory.h"
#include "rths_benchmark_plant.h"

namespace rpsd::servo {
namespace {

constexpr double kDt = 1.0 / 4096.0;

// The RTHS benchmark's nominal G_xu (Silva et al. 2020), as the closed loop's plant.
TransferFunctionPlantParameters benchmark_plant_parameters() {
  const BenchmarkTransferSystem b = rpsd::testing::rths_benchmark_nominal();
  TransferFunctionPlantParameters p;
  p.transfer_function = b.transfer_function();
  p.specimen_stiffness_n_per_m = b.specimen_stiffness_n_per_m;
  return p;
}

template <class Kind>
Kind example_of() {
  return Kind{};
}
template <>
ServoSystemParameters example_of() {
  return rpsd::testing::paper_rig();
}
template <>
PureDelayParameters example_of() {
  PureDelayParameters p;
  p.delay_s = 0.013;
  p.specimen_stiffness_n_per_m = 2e5;
  return p;
}
template <>
TransferFunctionPlantParameters example_of() {
  return benchmark_plant_parameters();
}
template <>
FeedbackControlledPlantParameters example_of() {
  FeedbackControlledPlantParameters p;
  p.plant = benchmark_plant_parameters();
  p.controller = PidGains{2.0, 95.0, 0.0, 0.0};  // the benchmark's sample G_C = 2 + 95/s
  return p;
}

template <class Kind>
class EveryPlantKind : public ::testing::Test {};
TYPED_TEST_SUITE(EveryPlantKind, rpsd::testing::KindTypes<PlantKinds>::type, rpsd::testing::KindNames);

TYPED_TEST(EveryPlantKind, AdvanceAndMeasureAllocateNothing) {
  std::unique_ptr<Plant> plant;
  ASSERT_NO_THROW(plant = make_plant(example_of<TypeParam>()))
      << "give example_of<" << TypeParam::kName << "> working parameters";
  plant->reset(0.0);
  double previous = 0.0, moved = 0.0, check = 0.0;
  rpsd::testing::begin_counting_allocations();
  for (int n = 1; n <= 8192; ++n) {  // 2 s of a 2 Hz, 5 mm sine
    const double command = 0.005 * std::sin(2.0 * std::numbers::pi * 2.0 * n * kDt);
    plant->advance(previous, command, kDt);
    previous = command;
    const PlantMeasurement m = plant->measure();
    moved = std::max(moved, std::abs(m.displacement_m));
    check += m.force_n;
  }
  EXPECT_EQ(rpsd::testing::end_counting_allocations().total(), 0);
  EXPECT_TRUE(std::isfinite(check));
  EXPECT_GT(moved, 0.002);  // the plant followed the command: the stepping path really ran
}

// Every kind that carries a coupled specimen's load exchanges under one (large-displacement
// geometry: Newton every period) without allocating; the others refuse to be configured for it.
TYPED_TEST(EveryPlantKind, CoupledSpecimenExchangeAllocatesNothing) {
  if constexpr (std::is_same_v<TypeParam, FeedbackControlledPlantParameters>) {
    EXPECT_THROW(coupled_plant_config(example_of<TypeParam>()), std::invalid_argument);
  } else {
    setups::PlanarGeometry g;
    g.geometry = setups::Geometry::kLargeDisplacement;
    g.dof_count = 2;
    g.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation, setups::DofMotion::kTranslationY};
    g.actuators[0] = {"bottom", {-2.0, 0.0}, {0.0, 0.0}};
    g.actuators[1] = {"top", {-2.0, 0.8}, {0.0, 0.8}};
    Eigen::MatrixXd k(2, 2), c(2, 2);
    k << 1.5e6, -1.5e6, -1.5e6, 2.0e6;
    c << 2e4, 0.0, 0.0, 1e4;
    const PlantConfig config = coupled_plant_config(example_of<TypeParam>());
    std::array<std::unique_ptr<Plant>, 2> owned = {make_plant(config), make_plant(config)};
    std::array<Plant*, 2> plants = {owned[0].get(), owned[1].get()};
    CoupledSpecimenActuator actuator(plants, setups::PlanarSetup(g), k, c);
    actuator.start(std::array<double, 2>{0.0, 0.0});
    ActuatorReading reading;
    double largest_load = 0.0;
    int faults = 0;
    rpsd::testing::begin_counting_allocations();
    for (int n = 1; n <= 4096; ++n) {  // 1 s of a 2 Hz, 5 mm sine on the top actuator
      const std::array<double, 2> command = {0.0, 0.005 * std::sin(2.0 * std::numbers::pi * 2.0 * n * kDt)};
      faults += actuator.exchange(command, kDt, reading) == ActuatorStatus::kOk ? 0 : 1;
      largest_load = std::max(largest_load, std::abs(reading.force_n[0]));
    }
    EXPECT_EQ(rpsd::testing::end_counting_allocations().total(), 0);
    EXPECT_EQ(faults, 0);
    EXPECT_GT(largest_load, 100.0);  // the specimen loaded the other actuator: the coupling ran
  }
}

}  // namespace
}  // namespace rpsd::servo
