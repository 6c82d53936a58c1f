#pragma once
// CR, the Chen-Ricles explicit method (2008): alpha1 = alpha2 = (4M + 2dt C + dt^2 K0)^-1 4M,
// v+ = v + dt alpha1 a, x+ = x + dt v + dt^2 alpha2 a (the command), M a+ = F+ - C v+ - R(x+).
// Eigenvalues equal average acceleration's on linear systems.
#include <string>

#include "rpsd/integrators/integrator_kind.h"
#include "rpsd/integrators/model_based_explicit_engine.h"

namespace rpsd::integrators {

class ChenRicles;

struct ChenRiclesParameters {
  static constexpr std::string_view kName = "chen_ricles";
  static constexpr std::string_view kSummary = "CR, the Chen-Ricles explicit method";
  using Integrator = ChenRicles;
  static ChenRiclesParameters read(config::Source&) { return {}; }
  static Aliases<ChenRiclesParameters> aliases() { return {{"cr", {}}}; }
  std::string describe() const { return "(none)"; }
};
using ChenRiclesParams [[deprecated("renamed ChenRiclesParameters (docs/migration.md)")]] = ChenRiclesParameters;

class ChenRicles final : public ModelBasedExplicitEngine {
 public:
  explicit ChenRicles(const ChenRiclesParameters& = {}) : ModelBasedExplicitEngine({0.0, 0.0, 0.5, 0.25}) {}
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
