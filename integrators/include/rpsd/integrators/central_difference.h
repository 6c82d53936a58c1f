#pragma once
// Central difference = explicit Newmark (beta = 0, gamma = 1/2), in the form used by
// OpenSees/OpenFresco: x+ = x + dt v + dt^2/2 a (the command);
// (M + dt/2 C) a+ = F+ - R(x+) - C (v + dt/2 a); v+ = v + dt/2 (a + a+).
// Stable for omega_max dt <= 2 (damping treated implicitly in velocity).
#include "rpsd/integrators/operator_splitting_engine.h"

namespace rpsd::integrators {

struct CentralDifferenceParams {};

class CentralDifference final : public OperatorSplittingEngine {
 public:
  explicit CentralDifference(const CentralDifferenceParams& = {}) : OperatorSplittingEngine({0.0, 0.0, 0.5}) {}
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
