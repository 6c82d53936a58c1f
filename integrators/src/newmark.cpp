#include "rpsd/integrators/newmark.h"

#include <sstream>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::integrators {

Aliases<NewmarkParameters> NewmarkParameters::aliases() {
  return {{"newmark_average", average_acceleration()},
          {"average_acceleration", average_acceleration()},
          {"newmark_linear", linear_acceleration()},
          {"linear_acceleration", linear_acceleration()}};
}

std::string NewmarkParameters::describe() const {
  std::ostringstream s;
  s << "beta=" << beta << " gamma=" << gamma << integrators::describe(fixed_iteration);
  return s.str();
}

void validate(const NewmarkParameters& p) {
  if (!(p.beta > 0.0) || !std::isfinite(p.beta))
    throw std::invalid_argument("newmark.beta must be > 0 (beta = 0 is central difference), got " +
                                std::to_string(p.beta));
  if (!(p.gamma >= 0.5) || !std::isfinite(p.gamma))
    throw std::invalid_argument("newmark.gamma must be >= 0.5 (smaller values amplify), got " +
                                std::to_string(p.gamma));
  validate(p.fixed_iteration);
}

double newmark_stability_limit(double beta, double gamma) {
  if (2.0 * beta >= gamma) return std::numeric_limits<double>::infinity();
  return 1.0 / std::sqrt(gamma / 2.0 - beta);
}

namespace {
const NewmarkParameters& checked(const NewmarkParameters& p) {
  validate(p);
  return p;
}
}  // namespace

Newmark::Newmark(const NewmarkParameters& p)
    : FixedIterationImplicitEngine({0.0, 0.0, checked(p).beta, p.gamma}, p.fixed_iteration), p_(p) {}

SchemeInfo Newmark::info() const {
  return {NewmarkParameters::kName, false, newmark_stability_limit(p_.beta, p_.gamma)};
}

}  // namespace rpsd::integrators
