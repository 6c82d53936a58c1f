// A weak planar_geometry for branches without the kinds' readers (branch `geometry` defines
// the real one, which replaces this at link time with no edit): the planar kind gives its
// geometry as it is; the others need their implementation and are refused by name.
// Delete this file once the kinds' implementation is merged.
#include <stdexcept>
#include <string>
#include <type_traits>

#include "rpsd/setups/setup_kinds.h"

namespace rpsd::setups {

__attribute__((weak)) PlanarGeometry planar_geometry(const SetupConfig& config) {
  return std::visit(
      [](const auto& kind) -> PlanarGeometry {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<Kind, PlanarActuatorsParameters>) {
          return kind.planar();
        } else {
          throw std::invalid_argument("experimental setup kind " + std::string(Kind::kName) +
                                      ": its geometry is not built on this branch (branch geometry)");
        }
      },
      config);
}

}  // namespace rpsd::setups
