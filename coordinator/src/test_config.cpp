#include "rpsd/coordinator/test_config.h"

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

}  // namespace rpsd::coordinator
