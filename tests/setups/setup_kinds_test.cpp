// Reading each kind from YAML text into the geometry it describes, and bad input refused at
// the key that is wrong, with file, line and key path.
#include <gtest/gtest.h>

#include <string>

#include "rpsd/config/key_table.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/yaml_reader.h"
#include "rpsd/setups/setup_kinds.h"

namespace rpsd::setups {
namespace {

SetupConfig read_setup(const std::string& yaml) {
  scenarios::MappingReader reader(scenarios::parse_yaml_text(yaml, "rig.yaml"), "rig.yaml", "setup");
  return read_setup_config(reader);
}

std::string error_of(const std::string& yaml) {
  try {
    read_setup(yaml);
  } catch (const scenarios::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

void expect_point(const Eigen::Vector2d& got, double x, double y) {
  EXPECT_NEAR(got.x(), x, 1e-15);
  EXPECT_NEAR(got.y(), y, 1e-15);
}

TEST(SetupKinds, ReadsOneActuator) {
  const SetupConfig c = read_setup(
      "kind: one_actuator\ngeometry: large_displacement\ndof: translation_y\nactuator_length_m: 1.25\n"
      "actuator_names: [vertical]\n");
  ASSERT_TRUE(std::holds_alternative<OneActuatorParameters>(c));
  const PlanarGeometry g = planar_geometry(c);
  EXPECT_EQ(g.geometry, Geometry::kLargeDisplacement);
  ASSERT_EQ(g.dof_count, 1);
  EXPECT_EQ(g.dofs[0], DofMotion::kTranslationY);
  EXPECT_EQ(g.actuators[0].name, "vertical");
  expect_point(g.actuators[0].fixed_end_m, 0.0, -1.25);
  expect_point(g.actuators[0].attachment_m, 0.0, 0.0);
}

TEST(SetupKinds, ReadsTwoActuators) {
  const SetupConfig c = read_setup(
      "kind: two_actuators\ngeometry: linear\nactuators_side: right\nactuator_lengths_m: [1.2, 1.5]\n"
      "distance_between_actuators_m: 0.8\nnewton_tolerance_m: 1.0e-10\nmax_newton_iterations: 12\n");
  const PlanarGeometry g = planar_geometry(c);
  EXPECT_EQ(g.geometry, Geometry::kLinear);
  ASSERT_EQ(g.dof_count, 2);
  EXPECT_EQ(g.dofs[0], DofMotion::kTranslationX);
  EXPECT_EQ(g.dofs[1], DofMotion::kRotation);
  EXPECT_EQ(g.actuators[0].name, "actuator_1");
  expect_point(g.actuators[0].fixed_end_m, 1.2, 0.0);
  expect_point(g.actuators[0].attachment_m, 0.0, 0.0);
  expect_point(g.actuators[1].fixed_end_m, 1.5, 0.8);
  expect_point(g.actuators[1].attachment_m, 0.0, 0.8);
  EXPECT_EQ(g.newton_tolerance_m, 1.0e-10);
  EXPECT_EQ(g.max_newton_iterations, 12);
}

// ESThreeActuatorsJntOff2d's La1..La3 = 1.1, 1.3, 1.4 and L1..L6 = 0.2, 0.6, 0.9, -, 0.15, 0.25.
TEST(SetupKinds, ReadsThreeActuatorsWithJointOffsets) {
  const SetupConfig c = read_setup(
      "kind: three_actuators\ngeometry: large_displacement\nhorizontal_actuator_side: left\n"
      "actuator_lengths_m: [1.1, 1.3, 1.4]\nleft_actuator_distance_m: 0.6\nright_actuator_distance_m: 0.9\n"
      "joint_offsets:\n  horizontal_actuator_offset_m: 0.2\n  left_actuator_offset_m: 0.15\n"
      "  right_actuator_offset_m: 0.25\n");
  const PlanarGeometry g = planar_geometry(c);
  ASSERT_EQ(g.dof_count, 3);
  EXPECT_EQ(g.dofs[2], DofMotion::kRotation);
  expect_point(g.actuators[0].attachment_m, -0.8, 0.0);
  expect_point(g.actuators[0].fixed_end_m, -1.9, 0.0);
  expect_point(g.actuators[1].attachment_m, -0.6, -0.15);
  expect_point(g.actuators[1].fixed_end_m, -0.6, -1.45);
  expect_point(g.actuators[2].attachment_m, 0.9, -0.25);
  expect_point(g.actuators[2].fixed_end_m, 0.9, -1.65);
  EXPECT_EQ(g.actuators[2].name, "right");
}

TEST(SetupKinds, ReadsThreeActuatorsWithoutJointOffsets) {
  const SetupConfig c = read_setup(
      "kind: three_actuators\ngeometry: linear\nhorizontal_actuator_side: right\n"
      "actuator_lengths_m: [1.1, 1.3, 1.4]\nleft_actuator_distance_m: 0.6\nright_actuator_distance_m: 0.9\n");
  const PlanarGeometry g = planar_geometry(c);
  expect_point(g.actuators[0].attachment_m, 0.9, 0.0);
  expect_point(g.actuators[0].fixed_end_m, 2.0, 0.0);
  expect_point(g.actuators[1].attachment_m, -0.6, 0.0);
}

TEST(SetupKinds, ReadsPlanar) {
  const SetupConfig c = read_setup(
      "kind: planar\ngeometry: large_displacement\ndofs: [rotation, translation_x]\nactuators:\n"
      "  - {name: upper, fixed_end_m: [-1.5, 0.8], attachment_m: [0.0, 0.8]}\n"
      "  - {name: lower, fixed_end_m: [-1.2, 0.0], attachment_m: [0.0, 0.0]}\n");
  const PlanarGeometry g = planar_geometry(c);
  ASSERT_EQ(g.dof_count, 2);
  EXPECT_EQ(g.dofs[0], DofMotion::kRotation);
  EXPECT_EQ(g.dofs[1], DofMotion::kTranslationX);
  EXPECT_EQ(g.actuators[0].name, "upper");
  expect_point(g.actuators[0].fixed_end_m, -1.5, 0.8);
  expect_point(g.actuators[1].attachment_m, 0.0, 0.0);
  EXPECT_NO_THROW(PlanarSetup{g});
}

constexpr const char* kTwo =
    "actuators_side: left\nactuator_lengths_m: [1.2, 1.5]\ndistance_between_actuators_m: 0.8\n";

TEST(SetupKinds, RefusesAnUnknownKindListingEveryName) {
  const std::string e = error_of(std::string("kind: two_actuator\ngeometry: linear\n") + kTwo);
  EXPECT_NE(e.find("rig.yaml:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("setup.kind"), std::string::npos) << e;
  EXPECT_NE(e.find("one_actuator, two_actuators, three_actuators or planar"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"two_actuators\""), std::string::npos) << e;
}

TEST(SetupKinds, RequiresTheGeometry) {
  const std::string missing = error_of(std::string("kind: two_actuators\n") + kTwo);
  EXPECT_NE(missing.find("setup.geometry: required key is missing"), std::string::npos) << missing;
  const std::string wrong = error_of(std::string("kind: two_actuators\ngeometry: large\n") + kTwo);
  EXPECT_NE(wrong.find("setup.geometry"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("linear or large_displacement"), std::string::npos) << wrong;
}

TEST(SetupKinds, RefusesAWrongDofName) {
  const std::string planar = error_of(
      "kind: planar\ngeometry: linear\ndofs: [translation_x, rotaton]\nactuators:\n"
      "  - {name: a, fixed_end_m: [-1.5, 0.8], attachment_m: [0.0, 0.8]}\n"
      "  - {name: b, fixed_end_m: [-1.2, 0.0], attachment_m: [0.0, 0.0]}\n");
  EXPECT_NE(planar.find("rig.yaml:3:"), std::string::npos) << planar;
  EXPECT_NE(planar.find("setup.dofs: \"rotaton\" is no DOF"), std::string::npos) << planar;
  EXPECT_NE(planar.find("did you mean \"rotation\""), std::string::npos) << planar;
  const std::string one =
      error_of("kind: one_actuator\ngeometry: linear\ndof: translation_z\nactuator_length_m: 1.0\n");
  EXPECT_NE(one.find("setup.dof"), std::string::npos) << one;
  EXPECT_NE(one.find("translation_x or translation_y"), std::string::npos) << one;
}

TEST(SetupKinds, RefusesAZeroLength) {
  const std::string one = error_of("kind: one_actuator\ngeometry: linear\ndof: translation_x\nactuator_length_m: 0\n");
  EXPECT_NE(one.find("rig.yaml:4:"), std::string::npos) << one;
  EXPECT_NE(one.find("setup.actuator_length_m"), std::string::npos) << one;
  const std::string two = error_of(
      "kind: two_actuators\ngeometry: linear\nactuators_side: left\nactuator_lengths_m: [1.2, 1.5]\n"
      "distance_between_actuators_m: 0.0\n");
  EXPECT_NE(two.find("setup.distance_between_actuators_m"), std::string::npos) << two;
  const std::string planar = error_of(
      "kind: planar\ngeometry: linear\ndofs: [translation_x]\nactuators:\n"
      "  - {name: a, fixed_end_m: [0.3, 0.1], attachment_m: [0.3, 0.1]}\n");
  EXPECT_NE(planar.find("setup.actuators[0].attachment_m"), std::string::npos) << planar;
  EXPECT_NE(planar.find("zero length"), std::string::npos) << planar;
}

// A geometry PlanarSetup refuses is reported at the key, with PlanarSetup's reason.
TEST(SetupKinds, RefusesASingularGeometryAtItsKey) {
  const std::string three = error_of(
      "kind: three_actuators\ngeometry: linear\nhorizontal_actuator_side: left\n"
      "actuator_lengths_m: [1.1, 1.3, 1.4]\nleft_actuator_distance_m: 0\nright_actuator_distance_m: 0\n");
  EXPECT_NE(three.find("setup.left_actuator_distance_m"), std::string::npos) << three;
  EXPECT_NE(three.find("singular"), std::string::npos) << three;
  const std::string planar = error_of(
      "kind: planar\ngeometry: linear\ndofs: [translation_x, rotation]\nactuators:\n"
      "  - {name: a, fixed_end_m: [-1.5, 0.0], attachment_m: [0.0, 0.0]}\n"
      "  - {name: b, fixed_end_m: [1.2, 0.0], attachment_m: [0.2, 0.0]}\n");
  EXPECT_NE(planar.find("setup.actuators"), std::string::npos) << planar;
  EXPECT_NE(planar.find("singular"), std::string::npos) << planar;
}

TEST(SetupKinds, RefusesListsThatDoNotFit) {
  const std::string lengths = error_of(
      "kind: two_actuators\ngeometry: linear\nactuators_side: left\nactuator_lengths_m: [1.2]\n"
      "distance_between_actuators_m: 0.8\n");
  EXPECT_NE(lengths.find("setup.actuator_lengths_m: expected 2 numbers, got 1"), std::string::npos) << lengths;
  const std::string count = error_of(
      "kind: planar\ngeometry: linear\ndofs: [translation_x, rotation]\nactuators:\n"
      "  - {name: a, fixed_end_m: [-1.5, 0.0], attachment_m: [0.0, 0.0]}\n");
  EXPECT_NE(count.find("setup.actuators: expected 2 actuators, one per DOF, got 1"), std::string::npos) << count;
  const std::string names =
      error_of(std::string("kind: two_actuators\ngeometry: linear\n") + kTwo + "actuator_names: [north, north]\n");
  EXPECT_NE(names.find("setup.actuator_names: \"north\" is given twice"), std::string::npos) << names;
  const std::string extra = error_of(std::string("kind: two_actuators\ngeometry: linear\n") + kTwo + "La1: 1.2\n");
  EXPECT_NE(extra.find("setup.La1: unknown key"), std::string::npos) << extra;
}

// The scenario reference lists a section's keys by reading it through a KeyTable: every kind's
// readers read all their keys before checking that they fit together, so that a listing that
// stops at a check has listed them all.
template <class Kind>
std::string listed_keys() {
  config::KeyTable table("setup");
  try {
    Kind::read(table, Geometry::kLinear);
  } catch (const config::ListingStopped&) {
  }
  std::string keys;
  for (const config::KeyRow& row : table.rows()) keys += row.path + " ";
  return keys;
}

TEST(SetupKinds, AListingSeesEveryKeyOfEveryKind) {
  EXPECT_EQ(listed_keys<OneActuatorParameters>(),
            "setup.dof setup.actuator_length_m setup.actuator_names setup.newton_tolerance_m "
            "setup.max_newton_iterations ");
  EXPECT_EQ(listed_keys<TwoActuatorsParameters>(),
            "setup.actuators_side setup.actuator_lengths_m setup.distance_between_actuators_m setup.actuator_names "
            "setup.newton_tolerance_m setup.max_newton_iterations ");
  EXPECT_EQ(listed_keys<ThreeActuatorsParameters>(),
            "setup.horizontal_actuator_side setup.actuator_lengths_m setup.left_actuator_distance_m "
            "setup.right_actuator_distance_m setup.joint_offsets setup.joint_offsets.horizontal_actuator_offset_m "
            "setup.joint_offsets.left_actuator_offset_m setup.joint_offsets.right_actuator_offset_m "
            "setup.actuator_names setup.newton_tolerance_m setup.max_newton_iterations ");
  EXPECT_EQ(listed_keys<PlanarActuatorsParameters>(),
            "setup.dofs setup.actuators setup.actuators[].name setup.actuators[].fixed_end_m "
            "setup.actuators[].attachment_m setup.newton_tolerance_m setup.max_newton_iterations ");
}

}  // namespace
}  // namespace rpsd::setups
