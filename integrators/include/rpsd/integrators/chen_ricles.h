#pragma once
// CR, the Chen-Ricles explicit method (2008): alpha1 = alpha2 = (4M + 2dt C + dt^2 K0)^-1 4M,
// v+ = v + dt alpha1 a, x+ = x + dt v + dt^2 alpha2 a (the command), M a+ = F+ - C v+ - R(x+).
// Eigenvalues equal average acceleration's on linear systems.
#include "rpsd/integrators/model_based_explicit_engine.h"

namespace rpsd::integrators {

struct ChenRiclesParams {};

class ChenRicles final : public ModelBasedExplicitEngine {
 public:
  explicit ChenRicles(const ChenRiclesParams& = {}) : ModelBasedExplicitEngine({0.0, 0.0, 0.5, 0.25}) {}
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
