#pragma once
// KR-alpha, the Kolay-Ricles explicit method (2014), rho_inf in [0, 1]; same alpha_m,
// alpha_f, gamma, beta as generalized-alpha, whose eigenvalues it shares on linear systems.
#include "rpsd/integrators/model_based_explicit_engine.h"

namespace rpsd::integrators {

struct KolayRiclesAlphaParams {
  double rho_inf = 0.8;
};

void validate(const KolayRiclesAlphaParams& p);

class KolayRiclesAlpha final : public ModelBasedExplicitEngine {
 public:
  explicit KolayRiclesAlpha(const KolayRiclesAlphaParams& p = {});
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
