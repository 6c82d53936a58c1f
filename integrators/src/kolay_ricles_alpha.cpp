#include "rpsd/integrators/kolay_ricles_alpha.h"

#include "rpsd/integrators/generalized_alpha.h"

#include <limits>

namespace rpsd::integrators {

void validate(const KolayRiclesAlphaParams& p) { (void)chung_hulbert_parameters(p.rho_inf); }

namespace {
ModelBasedCoefficients kr_coefficients(const KolayRiclesAlphaParams& p) {
  const auto c = chung_hulbert_parameters(p.rho_inf);
  return {c.alpha_m, c.alpha_f, c.gamma, c.beta};
}
}  // namespace

KolayRiclesAlpha::KolayRiclesAlpha(const KolayRiclesAlphaParams& p) : ModelBasedExplicitEngine(kr_coefficients(p)) {}

SchemeInfo KolayRiclesAlpha::info() const {
  return {Scheme::kKolayRiclesAlpha, "kolay_ricles_alpha", true, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
