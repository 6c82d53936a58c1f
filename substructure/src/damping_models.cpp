#include "rpsd/substructure/damping_models.h"

#include <cmath>

#include "rpsd/substructure/reading_ranges.h"

namespace rpsd::substructure {
namespace {

using config::Number;

Number ratio_range() { return Number::between(0.0, 1.0, "", "fraction of critical damping"); }

}  // namespace

std::optional<RayleighModesModel> RayleighModesModel::read(config::Source& damping) {
  auto r = damping.optional_section(kName, kSummary);
  if (!r) return std::nullopt;
  RayleighModesModel m;
  m.modes.mode_a = static_cast<int>(r->whole_number("mode_a", 1, 100000, "the first mode (1: the lowest)"));
  m.modes.mode_b = static_cast<int>(r->whole_number("mode_b", 1, 100000, "the second mode"));
  m.modes.damping_ratio_a = r->number("damping_ratio_a", ratio_range());
  m.modes.damping_ratio_b = r->number("damping_ratio_b", ratio_range());
  r->finish();
  return m;
}

DampingConfig RayleighModesModel::build(config::Source&, const Eigen::MatrixXd*) const { return modes; }

std::optional<ModalModel> ModalModel::read(config::Source& damping) {
  auto modal = damping.optional_section(kName, kSummary);
  if (!modal) return std::nullopt;
  ModalModel m;
  m.modal.damping_ratios = modal->numbers(
      "damping_ratios", Number::between(0.0, 1.0, "", "each mode's fraction of critical (one: every mode)"), 100000);
  modal->finish();
  return m;
}

DampingConfig ModalModel::build(config::Source&, const Eigen::MatrixXd*) const { return modal; }

std::optional<RayleighCoefficientsModel> RayleighCoefficientsModel::read(config::Source& damping) {
  auto c = damping.optional_section(kName, kSummary);
  if (!c) return std::nullopt;
  RayleighCoefficientsModel m;
  m.coefficients.a0_per_s = c->number_or("a0_per_s", 0.0, Number::between(0.0, 1e4, "1/s", "C = a0 M + a1 K0: a0"));
  m.coefficients.a1_s = c->number_or("a1_s", 0.0, Number::between(0.0, 10.0, "s", "C = a0 M + a1 K0: a1"));
  c->finish();
  return m;
}

DampingConfig RayleighCoefficientsModel::build(config::Source&, const Eigen::MatrixXd*) const { return coefficients; }

std::optional<SingleDofRatioModel> SingleDofRatioModel::read(config::Source& damping) {
  const auto zeta = damping.optional_number(kName, Number::between(0.0, 1.0, "", kSummary));
  const auto k = damping.optional_number(
      "of_stiffness_n_per_m",
      Number{"N/m", "one DOF: the stiffness the ratio refers to", 0.0, ranges::kMaxStiffnessNPerM, true});
  if (k && !zeta) damping.fail("of_stiffness_n_per_m", "only with damping_ratio");
  if (!zeta) return std::nullopt;
  return SingleDofRatioModel{*zeta, k};
}

DampingConfig SingleDofRatioModel::build(config::Source& damping, const Eigen::MatrixXd* mass) const {
  if (!of_stiffness_n_per_m) damping.fail(kName, "needs of_stiffness_n_per_m, the stiffness it refers to");
  if (!mass || mass->rows() != 1) damping.fail(kName, "a single damping ratio needs a one-DOF structure; use rayleigh");
  return DampingMatrix{linalg::StructuralMatrix(
      Eigen::MatrixXd::Constant(1, 1, 2.0 * damping_ratio * std::sqrt(*of_stiffness_n_per_m * (*mass)(0, 0))))};
}

}  // namespace rpsd::substructure
