#include "rpsd/coordinator/test_config.h"

#include <algorithm>

namespace rpsd::coordinator {

Eigen::Index structure_dofs(const TestConfig& config) {
  return std::visit(
      [](const auto& c) -> Eigen::Index {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofConfig>)
          return c.mass_kg.rows();
        else
          return static_cast<Eigen::Index>(c.floor_masses_kg.size());
      },
      config.structure);
}

namespace {

std::unique_ptr<substructure::NumericalModel> configured(
    const std::variant<substructure::LinearMdofConfig, substructure::ShearBuildingConfig>& structure) {
  return std::visit(
      [](const auto& c) -> std::unique_ptr<substructure::NumericalModel> {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofConfig>) {
          auto model = std::make_unique<substructure::LinearMdofModel>();
          model->configure(c);
          return model;
        } else {
          auto model = std::make_unique<substructure::ShearBuilding>();
          model->configure(c);
          return model;
        }
      },
      structure);
}

}  // namespace

std::unique_ptr<substructure::NumericalModel> make_numerical_model(const TestConfig& config) {
  if (!config.whole_structure_damping) return configured(config.structure);
  // The whole structure's C, from M and K0 with the specimens' stiffness; the numerical part
  // keeps it less the specimens' own damping (in model units, as their stiffness).
  const auto undamped = configured(config.structure);
  substructure::Partition partition;
  partition.configure(partition_config(config, undamped->dofs()));
  const linalg::StructuralMatrix k_whole = partition.with_specimen_stiffness(undamped->initial_stiffness());
  Eigen::MatrixXd c = substructure::build_damping(*config.whole_structure_damping, undamped->mass(), k_whole,
                                                  "whole_structure_damping: ")
                          .c.to_dense();
  for (const auto& e : config.experimental) {
    c(e.dof.dof, e.dof.dof) -= e.dof.force_scale * e.dof.displacement_scale * e.specimen_damping_n_s_per_m;
  }
  auto structure = config.structure;
  std::visit([&c](auto& s) { s.damping = substructure::DampingMatrix{linalg::StructuralMatrix(c)}; }, structure);
  return configured(structure);
}

substructure::PartitionConfig partition_config(const TestConfig& s, Eigen::Index dofs) {
  substructure::PartitionConfig split;
  split.dofs = dofs;
  for (const auto& e : s.experimental) split.experimental.push_back(e.dof);
  split.influence = s.influence;
  for (const auto& site : s.opensees_sites) {
    if (site.stiffness_n_per_m.size() == 0) continue;
    // The site's channels, in its DOF order.
    std::vector<Eigen::Index> channels;
    for (const auto& e : s.experimental) {
      if (e.site_id == site.adapter.site_id) channels.push_back(e.dof.actuator_channel);
    }
    std::sort(channels.begin(), channels.end());
    for (Eigen::Index i = 0; i < site.stiffness_n_per_m.rows(); ++i) {
      for (Eigen::Index j = i + 1; j < site.stiffness_n_per_m.cols(); ++j) {
        if (site.stiffness_n_per_m(i, j) != 0.0) {
          split.couplings.push_back({channels[static_cast<std::size_t>(i)], channels[static_cast<std::size_t>(j)],
                                     site.stiffness_n_per_m(i, j)});
        }
      }
    }
  }
  return split;
}

}  // namespace rpsd::coordinator
