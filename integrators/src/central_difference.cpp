#include "rpsd/integrators/central_difference.h"

namespace rpsd::integrators {

SchemeInfo CentralDifference::info() const { return {CentralDifferenceParameters::kName, true, 2.0}; }

}  // namespace rpsd::integrators
