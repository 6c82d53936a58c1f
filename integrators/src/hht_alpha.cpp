#include "rpsd/integrators/hht_alpha.h"

#include <sstream>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::integrators {

HhtAlphaParameters HhtAlphaParameters::read(config::Source& section) {
  HhtAlphaParameters p;
  p.alpha = section.number_or("alpha", p.alpha, alpha_range());
  return p;
}

std::string HhtAlphaParameters::describe() const {
  std::ostringstream s;
  s << "alpha=" << alpha << integrators::describe(fixed_iteration);
  return s.str();
}

void validate(const HhtAlphaParameters& p) {
  if (!(p.alpha >= -1.0 / 3.0 - 1e-12 && p.alpha <= 0.0))
    throw std::invalid_argument("hht_alpha.alpha must be in [-1/3, 0], got " + std::to_string(p.alpha));
  validate(p.fixed_iteration);
}

namespace {
ImplicitCoefficients hht_coefficients(const HhtAlphaParameters& p) {
  validate(p);
  const double a = p.alpha;
  return {0.0, -a, (1.0 - a) * (1.0 - a) / 4.0, (1.0 - 2.0 * a) / 2.0};
}
}  // namespace

HhtAlpha::HhtAlpha(const HhtAlphaParameters& p)
    : FixedIterationImplicitEngine(hht_coefficients(p), p.fixed_iteration) {}

SchemeInfo HhtAlpha::info() const {
  return {HhtAlphaParameters::kName, false, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
