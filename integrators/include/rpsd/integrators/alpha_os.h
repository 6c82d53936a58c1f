#pragma once
// alpha-OS, the alpha operator-splitting method (Combescure & Pegon), with the initial
// stiffness K_I = K0 as the implicit part. The predictor x~ = x + dt v + dt^2 (1/2 - beta) a
// is the command; the measured R~ is corrected by K_I (x+ - x~). alpha in [-1/3, 0],
// beta = (1-alpha)^2/4, gamma = (1-2 alpha)/2. With K_I = K its eigenvalues are HHT's.
#include <string>

#include "rpsd/integrators/integrator_kind.h"
#include "rpsd/integrators/operator_splitting_engine.h"

namespace rpsd::integrators {

class AlphaOs;

struct AlphaOsParameters {
  static constexpr std::string_view kName = "alpha_os";
  static constexpr std::string_view kSummary = "alpha operator splitting (Combescure & Pegon), K0 as the implicit part";
  using Integrator = AlphaOs;
  static AlphaOsParameters read(config::Source& section);  // alpha
  std::string describe() const;

  double alpha = -1.0 / 6.0;
};
using AlphaOsParams [[deprecated("renamed AlphaOsParameters (docs/migration.md)")]] = AlphaOsParameters;

void validate(const AlphaOsParameters& p);

class AlphaOs final : public OperatorSplittingEngine {
 public:
  explicit AlphaOs(const AlphaOsParameters& p = {});
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
