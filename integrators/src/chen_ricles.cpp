#include "rpsd/integrators/chen_ricles.h"

#include <limits>

namespace rpsd::integrators {

SchemeInfo ChenRicles::info() const {
  return {Scheme::kChenRicles, "chen_ricles", true, std::numeric_limits<double>::infinity()};
}

}  // namespace rpsd::integrators
