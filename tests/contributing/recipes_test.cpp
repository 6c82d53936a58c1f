// Every recipe of CONTRIBUTING.md, compiled exactly as written (the .inc files are extracted
// from it at build time), registered in a copy of its family's list and run for a step: a
// recipe that no longer fits its list fails here rather than in a contributor's hands.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/config/key_table.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/yaml_reader.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/substructure/damping_models.h"
#include "rpsd/substructure/reading_ranges.h"
#include "rpsd/substructure/story_spring.h"
#include "rpsd/substructure/structure_kinds.h"

namespace rpsd::compensation::recipe {
#include "compensator.inc"

// The class the recipe's prose describes, so that its parameters can be registered.
class MyCompensator final : public CommandCompensator {
 public:
  explicit MyCompensator(const MyParameters& p) : delay_s_(p.delay_s) {}
  void configure(double dt_s) override {
    if (!(dt_s > 0.0)) throw std::invalid_argument("dt_s must be positive");
  }
  void reset(double) noexcept override {}
  double command(double target_m) noexcept override { return target_m; }
  void observe(double, double) noexcept override {}
  double compensated_delay_s() const noexcept override { return delay_s_; }
  std::string_view name() const noexcept override { return MyParameters::kName; }

 private:
  double delay_s_;
};
}  // namespace rpsd::compensation::recipe

namespace rpsd::servo::recipe {
#include "plant.inc"

class MyPlant final : public Plant {
 public:
  explicit MyPlant(const MyPlantParameters& p) : p_(p) {}
  void reset(double displacement_m) override { x_m_ = displacement_m; }
  void advance(double, double command_end_m, double duration_s) override {
    x_m_ += (command_end_m - x_m_) * (1.0 - std::exp(-duration_s / p_.time_constant_s));
  }
  PlantMeasurement measure() const override {
    PlantMeasurement m;
    m.displacement_m = x_m_;
    m.force_n = p_.specimen_stiffness_n_per_m * x_m_;
    return m;
  }

 private:
  MyPlantParameters p_;
  double x_m_ = 0.0;
};
}  // namespace rpsd::servo::recipe

namespace rpsd::integrators::recipe {
#include "integrator.inc"
}  // namespace rpsd::integrators::recipe

namespace rpsd::substructure::recipe {
#include "story_spring.inc"
}  // namespace rpsd::substructure::recipe

namespace rpsd::substructure::damping_recipe {
#include "damping_model.inc"
}  // namespace rpsd::substructure::damping_recipe

namespace rpsd::substructure::structure_recipe {
#include "structure_kind.inc"
}  // namespace rpsd::substructure::structure_recipe

namespace rpsd {
namespace {

// A copy of a family's list with one more kind, as step 2 of a recipe makes it.
template <class List, class Kind>
struct Appended;
template <class... Kinds, class Kind>
struct Appended<config::KindList<Kinds...>, Kind> {
  using type = config::KindList<Kinds..., Kind>;
};

template <class List>
bool lists(std::string_view name) {
  for (std::string_view n : List::names())
    if (n == name) return true;
  return false;
}

TEST(ContributingRecipes, CompensatorReadsRegistersAndCommands) {
  using Kinds = Appended<compensation::CompensatorKinds, compensation::recipe::MyParameters>::type;
  ASSERT_TRUE(lists<Kinds>("my_scheme"));
  config::KeyTable table("compensation");
  const auto config = Kinds::read("my_scheme", table);
  ASSERT_TRUE(config.has_value());
  EXPECT_EQ(config::kind_name(*config), "my_scheme");
  ASSERT_EQ(table.rows().size(), 1U);
  EXPECT_EQ(table.rows()[0].path, "compensation.delay_s");
  auto compensator = std::visit(
      [](const auto& p) -> std::unique_ptr<compensation::CommandCompensator> {
        return std::make_unique<typename std::decay_t<decltype(p)>::Compensator>(p);
      },
      *config);
  compensator->configure(1.0 / 1024.0);
  compensator->reset(0.0);
  EXPECT_EQ(compensator->command(1e-3), 1e-3);
}

TEST(ContributingRecipes, PlantCarriesWhatEveryPlantCarriesAndAdvances) {
  using Kinds = Appended<servo::PlantKinds, servo::recipe::MyPlantParameters>::type;
  ASSERT_TRUE(lists<Kinds>("my_plant"));
  config::KeyTable table("servo");
  const auto config = Kinds::read("my_plant", table, 2.0e6);
  ASSERT_TRUE(config.has_value());
  // What read_plant_config, envelope_of, reading_ranges_of and specimen_stiffness_of ask of
  // every kind that is not a servo model or a feedback loop.
  const auto& p = std::get<servo::recipe::MyPlantParameters>(*config);
  EXPECT_FALSE(p.converters.any());
  p.converters.validate();
  const servo::Envelope rig = p.rig;
  (void)rig;
  (void)p.converters.reading_ranges();
  EXPECT_EQ(p.specimen_stiffness_n_per_m, 2.0e6);
  auto plant = std::make_unique<servo::recipe::MyPlantParameters::Model>(p);
  plant->reset(0.0);
  plant->advance(0.0, 1e-3, 1.0 / 1024.0);
  const double x = plant->measure().displacement_m;
  EXPECT_GT(x, 0.0);
  EXPECT_LT(x, 1e-3);
}

TEST(ContributingRecipes, IntegratorReadsRegistersAndSteps) {
  using Kinds = Appended<integrators::IntegratorKinds, integrators::recipe::MySchemeParameters>::type;
  ASSERT_TRUE(lists<Kinds>("my_scheme"));
  config::KeyTable table("integrator");
  const auto config = Kinds::read("my_scheme", table);
  ASSERT_TRUE(config.has_value());
  ASSERT_EQ(table.rows().size(), 1U);
  EXPECT_EQ(table.rows()[0].path, "integrator.alpha");
  const auto& p = std::get<integrators::recipe::MySchemeParameters>(*config);
  EXPECT_EQ(p.alpha, -0.1);
  EXPECT_FALSE(p.describe().empty());
  std::unique_ptr<integrators::Integrator> scheme = std::make_unique<integrators::recipe::MyScheme>(p);
  EXPECT_EQ(scheme->info().name, "my_scheme");
  // One step of an SDOF (m = 1 kg, k = 100 N/m) from 1 mm at rest: it moves towards zero.
  const Eigen::MatrixXd m = Eigen::MatrixXd::Ones(1, 1), c = Eigen::MatrixXd::Zero(1, 1),
                        k = Eigen::MatrixXd::Constant(1, 1, 100.0);
  scheme->configure(integrators::StructuralMatrices::dense(m, c, k), 0.01);
  const Eigen::VectorXd d0 = Eigen::VectorXd::Constant(1, 1e-3), zero = Eigen::VectorXd::Zero(1);
  scheme->initialize(d0, zero, k * d0, zero);
  ASSERT_EQ(scheme->begin_step(zero), integrators::StepStatus::kOk);
  for (int i = 0; i < scheme->iterations_per_step(); ++i) {
    ASSERT_EQ(scheme->set_measured_restoring_force(k * scheme->target_displacement()), integrators::StepStatus::kOk);
  }
  ASSERT_EQ(scheme->end_step(), integrators::StepStatus::kOk);
  EXPECT_LT(scheme->displacement()(0), 1e-3);
  EXPECT_GT(scheme->displacement()(0), 0.9e-3);
}

TEST(ContributingRecipes, StorySpringReadsRegistersAndTakesATrial) {
  using Kinds = Appended<substructure::StorySpringKinds, substructure::recipe::MySpringParameters>::type;
  ASSERT_TRUE(lists<Kinds>("my_spring"));
  config::KeyTable table("structure.stories[]");
  const auto config = Kinds::read("my_spring", table);
  ASSERT_TRUE(config.has_value());
  ASSERT_EQ(table.rows().size(), 1U);
  EXPECT_EQ(table.rows()[0].path, "structure.stories[].stiffness_n_per_m");
  const auto example = substructure::recipe::MySpringParameters::example();
  // The law by value, as StorySpring holds it for a list.
  typename substructure::SpringLaws<Kinds>::type law = substructure::recipe::MySpring(example);
  const double force = std::visit([](auto& s) { return s.trial(1e-3); }, law);
  std::visit([](auto& s) { s.commit(); }, law);
  EXPECT_DOUBLE_EQ(force, example.stiffness_n_per_m * 1e-3);
  EXPECT_DOUBLE_EQ(std::visit([](const auto& s) { return s.committed_force(); }, law), force);
  substructure::recipe::MySpringParameters bad;
  EXPECT_THROW(substructure::recipe::MySpring{bad}, std::invalid_argument);
}

// The section as a scenario would give it.
scenarios::MappingReader section(const std::string& yaml) {
  return scenarios::MappingReader(scenarios::parse_yaml_text(yaml, "recipe.yaml"), "recipe.yaml", "damping");
}

TEST(ContributingRecipes, DampingModelReadsRegistersAndBuildsC) {
  using Model = substructure::damping_recipe::StiffnessProportionalModel;
  using Models = Appended<substructure::DampingModels, Model>::type;
  ASSERT_TRUE(lists<Models>("stiffness_proportional"));
  auto d = section("stiffness_proportional: {damping_ratio: 0.05, frequency_hz: 2}");
  const substructure::DampingConfig config = substructure::read_damping_of<Models>(d, nullptr);
  const auto* c = std::get_if<substructure::RayleighCoefficients>(&config);
  ASSERT_NE(c, nullptr);
  EXPECT_DOUBLE_EQ(c->a1_s, 0.1 / (4.0 * std::numbers::pi));
  // The model's C: one DOF, k = 1e4 N/m.
  const linalg::StructuralMatrix m(Eigen::MatrixXd::Ones(1, 1)), k(Eigen::MatrixXd::Constant(1, 1, 1e4));
  const auto built = substructure::build_damping(config, m, k, "recipe: ");
  EXPECT_DOUBLE_EQ(built.c.to_dense()(0, 0), 1e4 * c->a1_s);
  // One model at most, the list's others included.
  auto two = section("stiffness_proportional: {damping_ratio: 0.05, frequency_hz: 2}\nmodal: {damping_ratios: [0.02]}");
  EXPECT_THROW((void)substructure::read_damping_of<Models>(two, nullptr), scenarios::ConfigError);
}

TEST(ContributingRecipes, StructureKindReadsRegistersAndRestores) {
  using Kind = substructure::structure_recipe::SdofStructure;
  using Kinds = Appended<substructure::StructureKinds, Kind>::type;
  ASSERT_TRUE(lists<Kinds>("sdof"));
  config::KeyTable table("structure");
  const auto read = Kinds::read("sdof", table);
  ASSERT_TRUE(read.has_value());
  ASSERT_EQ(table.rows().size(), 2U);
  Kind sdof;
  sdof.mass_kg = 1e3;
  sdof.stiffness_n_per_m = 1e6;
  const auto model = std::get<substructure::LinearMdofParameters>(sdof.model());
  substructure::LinearMdofModel structure;
  structure.configure(model);
  Eigen::VectorXd r(1);
  structure.restoring_force(Eigen::VectorXd::Constant(1, 1e-3), r);
  EXPECT_DOUBLE_EQ(r(0), 1e3);
  EXPECT_THROW((void)Kind{}.model(), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd
