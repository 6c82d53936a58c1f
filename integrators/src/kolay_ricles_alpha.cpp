#include "rpsd/integrators/kolay_ricles_alpha.h"

#include <sstream>

#include "rpsd/integrators/generalized_alpha.h"

#include <limits>

namespace rpsd::integrators {

KolayRiclesAlphaParams KolayRiclesAlphaParams::read(config::Source& section) {
  KolayRiclesAlphaParams p;
  p.rho_inf = section.number_or("rho_inf", p.rho_inf, rho_inf_range());
  return p;
}

std::string KolayRiclesAlphaParams::describe() const {
  std::ostringstream s;
  s << "rho_inf=" << rho_inf;
  return s.str();
}

void validate(const KolayRiclesAlphaParams& p) { (void)chung_hulbert_parameters(p.rho_inf); }

namespace {
ModelBasedCoefficients kr_coefficients(const KolayRiclesAlphaParams& p) {
  const auto c = chung_hulbert_parameters(p.rho_inf);
  return {c.alpha_m, c.alpha_f, c.gamma, c.beta};
}
}  // namespace

KolayRiclesAlpha::KolayRiclesAlpha(const KolayRiclesAlphaParams& p) : ModelBasedExplicitEngine(kr_coefficients(p)) {}

SchemeInfo KolayRiclesAlpha::info() const {
  return {KolayRiclesAlphaParams::kName, true, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
