// The scenario readers follow each family's list: every integrator the list registers is a
// scenario's integrator.scheme with its own keys, and the messages about story springs,
// damping models and structure kinds name every kind of their list.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../servo/paper_rig.h"
#include "example_files.h"
#include "kind_types.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/substructure/damping_models.h"
#include "rpsd/substructure/story_spring.h"
#include "rpsd/substructure/structure_kinds.h"

namespace rpsd::scenarios {
namespace {

hybrid_test::TestConfig test_with(const std::vector<std::string>& overrides) {
  std::vector<Override> parsed;
  for (const auto& o : overrides) parsed.push_back(parse_override(o));
  return std::get<hybrid_test::TestConfig>(load_study(example(), parsed).study);
}

std::string test_config_error(const std::vector<std::string>& overrides) {
  try {
    (void)test_with(overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

template <class Kind>
class EveryIntegratorKind : public ::testing::Test {};
TYPED_TEST_SUITE(EveryIntegratorKind, rpsd::testing::KindTypes<integrators::IntegratorKinds>::type,
                 rpsd::testing::KindNames);

TYPED_TEST(EveryIntegratorKind, IsAScenariosSchemeWithItsDefaultParameters) {
  const auto t = test_with({"integrator={scheme: " + std::string(TypeParam::kName) + "}"});
  ASSERT_TRUE(std::holds_alternative<TypeParam>(t.integrator));
  EXPECT_EQ(integrators::describe(t.integrator), TypeParam{}.describe());
}

TEST(IntegratorKinds, ASchemeReadsItsOwnKeysAndNoOther) {
  const auto t = test_with({"integrator={scheme: generalized_alpha, rho_inf: 0.6}"});
  EXPECT_DOUBLE_EQ(std::get<integrators::GeneralizedAlphaParameters>(t.integrator).rho_inf, 0.6);
  const auto hht = test_with({"integrator={scheme: hht_alpha, alpha: -0.2}"});
  EXPECT_DOUBLE_EQ(std::get<integrators::HhtAlphaParameters>(hht.integrator).alpha, -0.2);
  EXPECT_NE(test_config_error({"integrator={scheme: chang, rho_inf: 0.6}"}).find("integrator.rho_inf: unknown key"),
            std::string::npos);
  EXPECT_NE(test_config_error({"integrator={scheme: kolay_ricles_alpha, rho_inf: 1.5}"}).find("integrator.rho_inf"),
            std::string::npos);
}

TEST(StorySpringKinds, AnUnknownKindListsEveryKind) {
  const std::string error = test_config_error(
      {"structure={kind: shear_building, floor_masses_kg: [7080], stories: [{kind: elastic, stiffness_n_per_m: 1}]}"});
  EXPECT_NE(error.find("structure.stories[0].kind"), std::string::npos) << error;
  for (std::string_view name : substructure::StorySpringKinds::names())
    EXPECT_NE(error.find(std::string(name)), std::string::npos) << name << " in " << error;
}

TEST(StorySpringKinds, AShearBuildingReadsEachStorysKind) {
  const auto t = test_with(
      {"structure={kind: shear_building, floor_masses_kg: [7080], stories: [{kind: bilinear, stiffness_n_per_m: 1e6, "
       "yield_force_n: 1e3, post_yield_ratio: 0.1}]}"});
  const auto& building = std::get<substructure::ShearBuildingParameters>(t.structure);
  ASSERT_EQ(building.story_springs.size(), 1U);
  EXPECT_DOUBLE_EQ(std::get<substructure::BilinearSpringParameters>(building.story_springs[0]).yield_force_n, 1e3);
}

TEST(StructureKinds, AnUnknownKindListsEveryKind) {
  const std::string error = test_config_error({"structure.kind=tower"});
  for (std::string_view name : substructure::StructureKinds::names())
    EXPECT_NE(error.find(std::string(name)), std::string::npos) << name << " in " << error;
}

TEST(DampingModels, TwoModelsAreRefusedNamingEveryModel) {
  const std::string error =
      test_config_error({"structure.damping={rayleigh_coefficients: {a0_per_s: 0.1}, damping_ratio: 0.02, "
                         "of_stiffness_n_per_m: 700.8e3}"});
  EXPECT_NE(error.find("structure.damping.damping_ratio: give one of"), std::string::npos) << error;
  for (std::string_view name : substructure::DampingModels::names())
    EXPECT_NE(error.find(std::string(name)), std::string::npos) << name << " in " << error;
}

TEST(DampingModels, EachModelGivesItsDamping) {
  const auto t = test_with({"structure.damping={rayleigh_coefficients: {a0_per_s: 0.1, a1_s: 0.002}}"});
  const auto& c =
      std::get<substructure::RayleighCoefficients>(std::get<substructure::LinearMdofParameters>(t.structure).damping);
  EXPECT_DOUBLE_EQ(c.a0_per_s, 0.1);
  EXPECT_DOUBLE_EQ(c.a1_s, 0.002);
  EXPECT_NE(test_config_error({"structure.damping={damping_ratio: 0.02}"}).find("needs of_stiffness_n_per_m"),
            std::string::npos);
  EXPECT_NE(test_config_error({"structure.damping={of_stiffness_n_per_m: 1}"}).find("only with damping_ratio"),
            std::string::npos);
}

}  // namespace
}  // namespace rpsd::scenarios
