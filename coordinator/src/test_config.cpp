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

std::unique_ptr<substructure::NumericalModel> make_numerical_model(const TestConfig& config) {
  return std::visit(
      [](const auto& structure) -> std::unique_ptr<substructure::NumericalModel> {
        using C = std::decay_t<decltype(structure)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofConfig>) {
          auto model = std::make_unique<substructure::LinearMdofModel>();
          model->configure(structure);
          return model;
        } else {
          auto model = std::make_unique<substructure::ShearBuilding>();
          model->configure(structure);
          return model;
        }
      },
      config.structure);
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
