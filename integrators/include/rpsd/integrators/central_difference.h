#pragma once
// Central difference = explicit Newmark (beta = 0, gamma = 1/2), in the form used by
// OpenSees/OpenFresco: x+ = x + dt v + dt^2/2 a (the command);
// (M + dt/2 C) a+ = F+ - R(x+) - C (v + dt/2 a); v+ = v + dt/2 (a + a+).
// Stable for omega_max dt <= 2 (damping treated implicitly in velocity).
#include <string>

#include "rpsd/integrators/integrator_kind.h"
#include "rpsd/integrators/operator_splitting_engine.h"

namespace rpsd::integrators {

class CentralDifference;

struct CentralDifferenceParameters {
  static constexpr std::string_view kName = "central_difference";  // integrator.scheme in a scenario
  static constexpr std::string_view kSummary = "explicit Newmark (beta = 0, gamma = 1/2), stable for omega dt <= 2";
  using Integrator = CentralDifference;
  static CentralDifferenceParameters read(config::Source&) { return {}; }
  static Aliases<CentralDifferenceParameters> aliases() { return {{"cd", {}}}; }
  std::string describe() const { return "beta=0 gamma=0.5"; }
};
using CentralDifferenceParams [[deprecated("renamed CentralDifferenceParameters (docs/migration.md)")]] =
    CentralDifferenceParameters;

class CentralDifference final : public OperatorSplittingEngine {
 public:
  explicit CentralDifference(const CentralDifferenceParameters& = {}) : OperatorSplittingEngine({0.0, 0.0, 0.5}) {}
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
