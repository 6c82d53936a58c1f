#include "rpsd/integrators/generalized_alpha.h"

#include <sstream>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::integrators {

GeneralizedAlphaParameters GeneralizedAlphaParameters::read(config::Source& section) {
  GeneralizedAlphaParameters p;
  p.rho_inf = section.number_or("rho_inf", p.rho_inf, rho_inf_range());
  return p;
}

std::string GeneralizedAlphaParameters::describe() const {
  std::ostringstream s;
  s << "rho_inf=" << rho_inf << integrators::describe(fixed_iteration);
  return s.str();
}

AlphaParameters chung_hulbert_parameters(double rho_inf) {
  if (!(rho_inf >= 0.0 && rho_inf <= 1.0))
    throw std::invalid_argument("rho_inf must be in [0, 1], got " + std::to_string(rho_inf));
  const double am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  const double af = rho_inf / (rho_inf + 1.0);
  return {am, af, 0.5 - am + af, 1.0 / ((1.0 + rho_inf) * (1.0 + rho_inf))};
}

void validate(const GeneralizedAlphaParameters& p) {
  (void)chung_hulbert_parameters(p.rho_inf);
  validate(p.fixed_iteration);
}

namespace {
ImplicitCoefficients ga_coefficients(const GeneralizedAlphaParameters& p) {
  validate(p);
  const auto c = chung_hulbert_parameters(p.rho_inf);
  return {c.alpha_m, c.alpha_f, c.beta, c.gamma};
}
}  // namespace

GeneralizedAlpha::GeneralizedAlpha(const GeneralizedAlphaParameters& p)
    : FixedIterationImplicitEngine(ga_coefficients(p), p.fixed_iteration) {}

SchemeInfo GeneralizedAlpha::info() const {
  return {GeneralizedAlphaParameters::kName, false, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
