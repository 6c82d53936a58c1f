#include "rpsd/compensation/compensator_factory.h"

namespace rpsd::compensation {

std::unique_ptr<CommandCompensator> make_compensator(const CompensatorConfig& config, double dt_s, int channel) {
  std::unique_ptr<CommandCompensator> compensator = std::visit(
      [channel](const auto& p) -> std::unique_ptr<CommandCompensator> {
        using Compensator = typename std::decay_t<decltype(p)>::Compensator;
        if constexpr (std::is_same_v<Compensator, ExternalCompensator>) {
          return std::make_unique<ExternalCompensator>(p, channel);
        } else {
          return std::make_unique<Compensator>(p);
        }
      },
      config);
  compensator->configure(dt_s);
  return compensator;
}

}  // namespace rpsd::compensation
