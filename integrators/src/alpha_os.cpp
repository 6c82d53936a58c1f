#include "rpsd/integrators/alpha_os.h"

#include <sstream>

#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::integrators {

AlphaOsParameters AlphaOsParameters::read(config::Source& section) {
  AlphaOsParameters p;
  p.alpha = section.number_or("alpha", p.alpha, alpha_range());
  return p;
}

std::string AlphaOsParameters::describe() const {
  std::ostringstream s;
  s << "alpha=" << alpha;
  return s.str();
}

void validate(const AlphaOsParameters& p) {
  if (!(p.alpha >= -1.0 / 3.0 - 1e-12 && p.alpha <= 0.0))
    throw std::invalid_argument("alpha_os.alpha must be in [-1/3, 0], got " + std::to_string(p.alpha));
}

namespace {
OperatorSplittingCoefficients os_coefficients(const AlphaOsParameters& p) {
  validate(p);
  const double a = p.alpha;
  return {a, (1.0 - a) * (1.0 - a) / 4.0, (1.0 - 2.0 * a) / 2.0};
}
}  // namespace

AlphaOs::AlphaOs(const AlphaOsParameters& p) : OperatorSplittingEngine(os_coefficients(p)) {}

SchemeInfo AlphaOs::info() const { return {AlphaOsParameters::kName, true, std::numeric_limits<double>::infinity()}; }

}  // namespace rpsd::integrators
