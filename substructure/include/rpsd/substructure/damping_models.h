// The damping models a file may give in a `damping:` section (a structure's, and
// `whole_structure_damping:`), registered in one place (the list below). Each names the key
// it is given under, reads its keys when it is given and, once the section is finished,
// builds the DampingConfig it stands for; at most one model may be given, none is undamped.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/kind_list.h"
#include "rpsd/config/source.h"
#include "rpsd/substructure/damping.h"

namespace rpsd::substructure {

// rayleigh: {mode_a, mode_b, damping_ratio_a, damping_ratio_b}
struct RayleighModesModel {
  static constexpr std::string_view kName = "rayleigh";
  static constexpr std::string_view kSummary = "Rayleigh damping fitted to two modes";
  static std::optional<RayleighModesModel> read(config::Source& damping);
  DampingConfig build(config::Source& damping, const Eigen::MatrixXd* mass) const;
  RayleighFromModes modes;
};

// modal: {damping_ratios}
struct ModalModel {
  static constexpr std::string_view kName = "modal";
  static constexpr std::string_view kSummary = "classical damping with a ratio per mode";
  static std::optional<ModalModel> read(config::Source& damping);
  DampingConfig build(config::Source& damping, const Eigen::MatrixXd* mass) const;
  ModalDamping modal;
};

// rayleigh_coefficients: {a0_per_s, a1_s}. C = a0 M + a1 K0 as OpenSees' `rayleigh a0 0 a1 0`
// gives it: the same C when a model is split between rpsd and OpenSees, where damping fitted
// to this part's modes would differ.
struct RayleighCoefficientsModel {
  static constexpr std::string_view kName = "rayleigh_coefficients";
  static constexpr std::string_view kSummary = "Rayleigh damping given by its coefficients";
  static std::optional<RayleighCoefficientsModel> read(config::Source& damping);
  DampingConfig build(config::Source& damping, const Eigen::MatrixXd* mass) const;
  RayleighCoefficients coefficients;
};

// damping_ratio and of_stiffness_n_per_m, keys of the section itself. One DOF:
// c = 2 zeta sqrt(k m); the stiffness is the structure's total (numerical plus the
// experimental estimate), given here explicitly.
struct SingleDofRatioModel {
  static constexpr std::string_view kName = "damping_ratio";
  static constexpr std::string_view kSummary = "one DOF: fraction of critical";
  static std::optional<SingleDofRatioModel> read(config::Source& damping);
  DampingConfig build(config::Source& damping, const Eigen::MatrixXd* mass) const;
  double damping_ratio = 0.0;
  std::optional<double> of_stiffness_n_per_m;
};

using DampingModels = config::KindList<RayleighModesModel, ModalModel, RayleighCoefficientsModel, SingleDofRatioModel>;

// The damping a `damping:` section gives (finished), one of the models of `Models`; `mass`
// is the structure's when it is known (a single ratio needs it). Errors name the section's
// key (config::Source::fail).
template <class Models>
DampingConfig read_damping_of(config::Source& damping, const Eigen::MatrixXd* mass) {
  std::vector<std::string_view> given;
  std::function<DampingConfig()> build;  // the given model's
  Models::for_each([&](auto kind) {
    using Model = typename decltype(kind)::type;
    if (auto model = Model::read(damping)) {
      given.push_back(Model::kName);
      build = [&damping, mass, m = *model] { return m.build(damping, mass); };
    }
  });
  damping.finish();
  if (given.size() > 1) {
    damping.fail(given[1], "give one of " + config::listed(Models::names()) + ", not both " + std::string(given[0]) +
                               " and " + std::string(given[1]));
  }
  return build ? build() : DampingConfig{Undamped{}};
}
inline DampingConfig read_damping(config::Source& damping, const Eigen::MatrixXd* mass) {
  return read_damping_of<DampingModels>(damping, mass);
}

}  // namespace rpsd::substructure
