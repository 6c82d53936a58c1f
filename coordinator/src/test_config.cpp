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

}  // namespace rpsd::coordinator
