#include "rpsd/compensation/compensator_factory.h"

namespace rpsd::compensation {

std::unique_ptr<CommandCompensator> make_compensator(const CompensatorConfig& config, double dt_s) {
  std::unique_ptr<CommandCompensator> compensator = std::visit(
      [](const auto& p) -> std::unique_ptr<CommandCompensator> {
        return std::make_unique<typename std::decay_t<decltype(p)>::Compensator>(p);
      },
      config);
  compensator->configure(dt_s);
  return compensator;
}

}  // namespace rpsd::compensation
