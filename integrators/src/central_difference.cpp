#include "rpsd/integrators/central_difference.h"

namespace rpsd::integrators {

SchemeInfo CentralDifference::info() const {
  return {Scheme::central_difference, "central_difference", true, 2.0};
}

}  // namespace rpsd::integrators
