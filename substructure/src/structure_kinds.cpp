#include "rpsd/substructure/structure_kinds.h"

#include <utility>
#include <vector>

#include "rpsd/linalg/dense_from_rows.h"
#include "rpsd/substructure/damping_models.h"
#include "rpsd/substructure/reading_ranges.h"
#include "rpsd/substructure/story_spring.h"

namespace rpsd::substructure {
namespace {

using config::Number;

// An inline matrix (rows, a diagonal or one number) has at most this many rows: larger
// structures come as Matrix Market files.
constexpr std::size_t kMaxInlineDofs = 200;

DampingConfig optional_damping(config::Source& st, const Eigen::MatrixXd* mass) {
  auto d = st.optional_section("damping", "the structure's damping (none: undamped)");
  return d ? read_damping(*d, mass) : DampingConfig{Undamped{}};
}

}  // namespace

LinearStructure LinearStructure::read(config::Source& st) {
  LinearStructure s;
  const Eigen::MatrixXd m = linalg::dense_from_rows(
      st.matrix("mass_kg", Number{"kg", "the mass matrix", 0.0, ranges::kMaxMassKg}, kMaxInlineDofs));
  const Eigen::MatrixXd k = linalg::dense_from_rows(st.matrix(
      "stiffness_n_per_m", Number{"N/m", "the stiffness matrix", 0.0, ranges::kMaxStiffnessNPerM}, kMaxInlineDofs));
  s.config.damping = optional_damping(st, &m);
  if (m.rows() != k.rows() || m.cols() != k.cols()) st.fail("stiffness_n_per_m", "must have the size of mass_kg");
  s.config.mass_kg = linalg::StructuralMatrix(m);
  s.config.stiffness_n_per_m = linalg::StructuralMatrix(k);
  return s;
}

StructureConfig LinearStructure::model() const {
  LinearMdofModel probe;
  probe.configure(config);  // validates: symmetric, positive definite, sizes
  return config;
}

MatrixMarketStructure MatrixMarketStructure::read(config::Source& st) {
  MatrixMarketStructure s;
  s.files.mass_file = st.relative_file("mass_file", "M, a Matrix Market file (relative to this file)");
  s.files.stiffness_file = st.relative_file("stiffness_file", "K, a Matrix Market file");
  if (auto c = st.optional_relative_file("damping_file", "C, a Matrix Market file (or damping:)"))
    s.files.damping_file = *c;
  s.damping = optional_damping(st, nullptr);
  return s;
}

StructureConfig MatrixMarketStructure::model() const {
  LinearMdofParameters c = linear_config_from_matrix_market(files, damping);
  LinearMdofModel probe;
  probe.configure(c);
  return c;
}

ShearBuildingStructure ShearBuildingStructure::read(config::Source& st) {
  ShearBuildingStructure s;
  ShearBuildingParameters& c = s.config;
  c.floor_masses_kg = st.numbers(
      "floor_masses_kg", Number{"kg", "each floor's mass, bottom up", 0.0, ranges::kMaxMassKg, true}, kMaxInlineDofs);
  for (auto& story : st.sections("stories", kMaxInlineDofs, "each story's spring, bottom up")) {
    const std::string kind = story->choice("kind", StorySpringKinds::names(), "the story's spring");
    c.story_springs.push_back(*StorySpringKinds::read(kind, *story));
    story->finish();
  }
  c.damping = optional_damping(st, nullptr);
  if (c.story_springs.size() != c.floor_masses_kg.size()) st.fail("stories", "needs one story per floor mass");
  return s;
}

StructureConfig ShearBuildingStructure::model() const {
  ShearBuilding probe;
  probe.configure(config);
  return config;
}

ExternalStructure ExternalStructure::read(config::Source& st) {
  ExternalStructure s;
  // The name first: the matrices' reader checks how they fit, which ends a listing.
  s.name = st.text("name", "which of the host program's structures (a Python callable's name in callables=)");
  s.matrices = LinearStructure::read(st);
  const bool well_formed =
      !s.name.empty() && s.name.size() <= 64 &&
      s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") ==
          std::string::npos;
  if (!well_formed) st.fail("name", "expected 1 to 64 letters, digits, '_', '-' or '.'");
  return s;
}

StructureConfig ExternalStructure::model() const {
  LinearMdofModel probe;
  probe.configure(matrices.config);  // the matrices as the linear kind checks them
  return ExternalStructureParameters{matrices.config, name, nullptr};
}

}  // namespace rpsd::substructure
