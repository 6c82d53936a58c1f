#include "rpsd/integrators/central_difference.h"

namespace rpsd::integrators {

SchemeInfo CentralDifference::info() const { return {CentralDifferenceParams::kName, true, 2.0}; }

}  // namespace rpsd::integrators
