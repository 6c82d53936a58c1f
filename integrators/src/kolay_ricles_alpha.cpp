#include "rpsd/integrators/kolay_ricles_alpha.h"

#include <sstream>

#include "rpsd/integrators/generalized_alpha.h"

#include <limits>

namespace rpsd::integrators {

KolayRiclesAlphaParameters KolayRiclesAlphaParameters::read(config::Source& section) {
  KolayRiclesAlphaParameters p;
  p.rho_inf = section.number_or("rho_inf", p.rho_inf, rho_inf_range());
  return p;
}

std::string KolayRiclesAlphaParameters::describe() const {
  std::ostringstream s;
  s << "rho_inf=" << rho_inf;
  return s.str();
}

void validate(const KolayRiclesAlphaParameters& p) { (void)chung_hulbert_parameters(p.rho_inf); }

namespace {
ModelBasedCoefficients kr_coefficients(const KolayRiclesAlphaParameters& p) {
  const auto c = chung_hulbert_parameters(p.rho_inf);
  return {c.alpha_m, c.alpha_f, c.gamma, c.beta};
}
}  // namespace

KolayRiclesAlpha::KolayRiclesAlpha(const KolayRiclesAlphaParameters& p)
    : ModelBasedExplicitEngine(kr_coefficients(p)) {}

SchemeInfo KolayRiclesAlpha::info() const {
  return {KolayRiclesAlphaParameters::kName, true, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
