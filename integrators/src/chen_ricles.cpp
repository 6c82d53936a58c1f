#include "rpsd/integrators/chen_ricles.h"

#include <limits>

namespace rpsd::integrators {

SchemeInfo ChenRicles::info() const {
  return {ChenRiclesParameters::kName, true, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
